// Sensor estimation for plain folders of scans (see sensor_estimate.hpp).
#include "datasets/sensor_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "core/log.hpp"
#include "datasets/sensor_beams.hpp"
#include "io/scan_io.hpp"

namespace sgnlf {
namespace {

std::string fmt(const char* f, double a, double b = 0.0, double c = 0.0) {
  char buf[96];
  std::snprintf(buf, sizeof buf, f, a, b, c);
  return buf;
}

// Degrees of azimuth (1° bins) holding at least 1 % of the mean count per degree.
double azimuth_coverage_deg(const std::vector<ScanSample>& scans) {
  std::vector<size_t> bins(360, 0);
  size_t n = 0;
  for (const auto& s : scans)
    for (const auto& p : s.points) {
      if (!(detail::range_m(p) > 0.0)) continue;
      const double a = std::atan2(double(p.y), double(p.x)) * 180.0 / M_PI + 180.0;
      ++bins[std::min<size_t>(359, size_t(std::max(0.0, a)))];
      ++n;
    }
  const double min_count = std::max(1.0, 0.01 * double(n) / 360.0);
  return double(std::count_if(bins.begin(), bins.end(), [&](size_t c) { return double(c) >= min_count; }));
}

// The q-quantile of sorted values (nearest rank).
double quantile(const std::vector<double>& sorted, double q) {
  return sorted[size_t(std::lround(q * double(sorted.size() - 1)))];
}

// Names what the estimate got wrong when it keeps too few points.
std::string diagnose(const Sensor& s, const std::vector<ScanSample>& scans) {
  size_t above = 0, below = 0, columns = 0;
  const double row_step = s.fov_deg / s.height, col_step = 360.0 / s.width;
  for (const auto& sc : scans)
    for (const auto& p : sc.points) {
      if (!s.in_range(detail::range_m(p))) continue;
      const long r = std::lround(s.height - (detail::elevation_deg(p) + s.fov_deg - s.fov_up_deg) / row_step);
      const long c = std::lround((180.0 - std::atan2(double(p.y), double(p.x)) * 180.0 / M_PI) / col_step);
      if (r < 0) ++above;
      else if (r >= s.height) ++below;
      else if (c < 0 || c >= s.width) ++columns;
    }
  if (columns > above + below) return "the width estimate puts " + std::to_string(columns) + " points outside the columns";
  return "the rows / field-of-view estimate leaves " + std::to_string(above) + " points above the top row and " +
         std::to_string(below) + " below the bottom row";
}

}  // namespace

std::vector<ScanSample> read_scan_sample(const std::vector<std::string>& files, int max_scans) {
  std::vector<ScanSample> out;
  if (files.empty() || max_scans < 1) return out;
  const size_t n = files.size(), m = std::min(n, size_t(max_scans));
  for (size_t k = 0; k < m; ++k) {
    const size_t i = m == 1 ? 0 : k * (n - 1) / (m - 1);
    ScanSample s;
    io::ScanExtras ex;
    s.points = io::read_scan(files[i], nullptr, &ex);
    if (ex.has_ring) s.ring = std::move(ex.ring);
    out.push_back(std::move(s));
  }
  return out;
}

double kept_fraction(const Sensor& s, const std::vector<ScanSample>& scans, size_t* in_range) {
  size_t total = 0, kept = 0;
  for (const auto& sc : scans) {
    ProjectionStats st;
    (void)project_points(s, sc.points, &st);
    total += st.projected + st.occluded + st.out_of_fov;
    kept += st.projected + st.occluded;
  }
  if (in_range) *in_range = total;
  return total ? double(kept) / double(total) : 0.0;
}

SensorEstimate estimate_sensor(const std::vector<ScanSample>& scans, const SensorEstimateOptions& o) {
  if (scans.empty()) throw Error("sensor estimate: no scans");
  SensorEstimate e;
  e.azimuth_coverage_deg = azimuth_coverage_deg(scans);
  if (e.azimuth_coverage_deg < o.min_azimuth_coverage_deg)
    throw Error("sensor estimate: the scans cover " + fmt("%.0f", e.azimuth_coverage_deg) +
                "° of azimuth (< " + fmt("%.0f", o.min_azimuth_coverage_deg) +
                "°): not a spinning 360° sensor, and the sensor model has no horizontal field of "
                "view to estimate; give --sensor FILE");
  const detail::Beams b = detail::find_beams(scans);
  e.from_rings = b.from_rings;
  e.beam_elevation_deg = b.elevation_deg;
  Sensor& s = e.sensor;
  s.name = "estimated";
  s.height = b.rows;
  s.fov_up_deg = b.elevation_deg.front();
  // Rows are one step apart and the top and bottom beams sit on the first and last rows.
  s.fov_deg = (b.elevation_deg.front() - b.elevation_deg.back()) * b.rows / (b.rows - 1);
  const int measured_width = detail::estimate_width(scans, b);
  s.width = std::max(kWidthMultiple, int(std::lround(double(measured_width) / kWidthMultiple)) * kWidthMultiple);
  if (long(s.height) * s.width > kMaxSensorPixels) {
    const int w = std::max(1, int(kMaxSensorPixels / s.height) / kWidthMultiple) * kWidthMultiple;
    log::warn("sensor estimate: width ", s.width, " × ", s.height, " rows exceeds the pixel limit; width ", w);
    s.width = w;
  }
  std::vector<double> r;
  for (const auto& sc : scans)
    for (const auto& p : sc.points)
      if (detail::range_m(p) > 0.0) r.push_back(detail::range_m(p));
  std::sort(r.begin(), r.end());
  if (r.empty()) throw Error("sensor estimate: ranges: the scans hold no point");
  s.min_range_m = std::floor(0.9 * quantile(r, 0.001) * 10.0) / 10.0;
  // Returns so near that their elevation fits no beam are the vehicle itself or the head's
  // housing (a nuScenes sweep holds ~2 000 of them within 0.75 m): the sensor's minimum range.
  const double half_row = 0.5 * s.fov_deg / s.height, top = s.fov_up_deg + half_row,
               bottom = s.fov_up_deg - s.fov_deg + half_row;
  double near_misfit = 0.0;
  for (const auto& sc : scans)
    for (const auto& p : sc.points) {
      const double d = detail::range_m(p), el = detail::elevation_deg(p);
      if (d <= detail::kNearM && (el > top || el <= bottom)) near_misfit = std::max(near_misfit, d);
    }
  s.min_range_m = std::max(s.min_range_m, std::ceil(near_misfit * 10.0) / 10.0);
  s.max_range_m = std::min(1e4, std::ceil(1.1 * quantile(r, 0.999)));
  s.rate_hz = o.rate_hz;
  s.sweep = preset_sweep_timing(s.name);
  if (o.adjust) o.adjust(s);
  s.validate();
  e.kept_fraction = kept_fraction(s, scans, &e.in_range_points);
  if (e.kept_fraction < o.min_kept_fraction)
    throw Error("sensor estimate failed its check: rows " + std::to_string(s.height) +
                (e.from_rings ? " (ring field)" : " (elevation histogram peaks)") + ", field of view " +
                fmt("%.2f° up, %.2f° in all", s.fov_up_deg, s.fov_deg) + ", width " + std::to_string(s.width) +
                " keep " + fmt("%.1f", 100.0 * e.kept_fraction) + " % of the " +
                std::to_string(e.in_range_points) + " in-range points (needs " +
                fmt("%.0f", 100.0 * o.min_kept_fraction) + " %): " + diagnose(s, scans) +
                "; give --sensor NAME|FILE");
  log::info("sensor estimate (", scans.size(), " scans): ", s.height, " rows (",
            e.from_rings ? "ring field" : "elevation histogram peaks", "), fov_up ", s.fov_up_deg, "°, fov ",
            s.fov_deg, "°, width ", s.width, " (measured ", measured_width, "), range ", s.min_range_m, "-", s.max_range_m, " m; keeps ",
            100.0 * e.kept_fraction, " % of ", e.in_range_points, " in-range points");
  return e;
}

std::string matching_preset(const Sensor& est) {
  for (const std::string name : {"kitti360", "nuscenes"}) {
    const Sensor p = sensor_preset(name);
    const double fov_tol = 0.1 * p.fov_deg;
    if (std::abs(est.height - p.height) <= p.height / 8.0 && std::abs(est.fov_up_deg - p.fov_up_deg) <= fov_tol &&
        std::abs(est.fov_deg - p.fov_deg) <= fov_tol && double(est.width) >= 0.9 * p.width)
      return name;
  }
  return "";
}

}  // namespace sgnlf
