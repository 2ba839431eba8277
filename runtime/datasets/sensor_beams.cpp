// Beams and azimuth resolution of a scan sample (see sensor_beams.hpp).
#include "datasets/sensor_beams.hpp"

#include <algorithm>
#include <map>

#include "core/error.hpp"

namespace sgnlf::detail {
namespace {

constexpr double kBinDeg = 0.02;  // elevation histogram bin (beams are >= 0.1° apart)

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + long(m), v.end());
  return v[m];
}

Beams beams_from_rings(const std::vector<ScanSample>& scans) {
  Beams b;
  b.from_rings = true;
  std::map<int, std::vector<double>> elev, elev_near;
  for (const auto& s : scans)
    for (size_t i = 0; i < s.points.size(); ++i)
      (range_m(s.points[i]) > kNearM ? elev : elev_near)[s.ring[i]].push_back(elevation_deg(s.points[i]));
  for (auto& [ring, e] : elev_near)
    if (!elev.count(ring)) elev[ring] = std::move(e);  // a ring seen only near the sensor
  if (elev.size() < 2)
    throw Error("sensor estimate: rows: the ring field names " + std::to_string(elev.size()) +
                " beam(s); a range image needs at least 2");
  b.rows = elev.rbegin()->first - elev.begin()->first + 1;
  for (const auto& [ring, e] : elev) b.elevation_deg.push_back(median(e));
  std::sort(b.elevation_deg.rbegin(), b.elevation_deg.rend());
  for (const auto& s : scans) b.beam.emplace_back(s.ring.begin(), s.ring.end());
  return b;
}

Beams beams_from_elevations(const std::vector<ScanSample>& scans) {
  std::vector<double> e;
  for (const auto& s : scans)
    for (const auto& p : s.points)
      if (range_m(p) > kNearM) e.push_back(elevation_deg(p));
  if (e.size() < 100)  // a sample of near points only: use them all
    for (const auto& s : scans)
      for (const auto& p : s.points)
        if (range_m(p) > 0.0 && range_m(p) <= kNearM) e.push_back(elevation_deg(p));
  if (e.empty()) throw Error("sensor estimate: rows: the scans hold no point");
  const double lo = *std::min_element(e.begin(), e.end());
  const double hi = *std::max_element(e.begin(), e.end());
  const size_t nbins = size_t((hi - lo) / kBinDeg) + 1;
  auto bin_of = [&](double x) { return std::min(nbins - 1, size_t(std::max(0.0, (x - lo) / kBinDeg))); };
  std::vector<size_t> count(nbins, 0);
  for (double x : e) ++count[bin_of(x)];
  // Occupied bins: at least 5 % of the typical occupied bin, so that stray returns between
  // two beams (noise, a real head's spread) do not join them into one.
  std::vector<double> nonzero;
  for (size_t c : count)
    if (c > 0) nonzero.push_back(double(c));
  const double min_count = std::max(1.0, 0.05 * median(nonzero));
  std::vector<int> cluster(nbins, -1);
  int n = 0;
  for (size_t k = 0; k < nbins; ++k) {
    if (double(count[k]) < min_count) continue;
    cluster[k] = (k > 0 && cluster[k - 1] >= 0) ? cluster[k - 1] : n++;
  }
  // Clusters, bottom first; the mean elevation of each.
  std::vector<double> sum(size_t(n), 0.0), cnt(size_t(n), 0.0);
  for (double x : e) {
    const int c = cluster[bin_of(x)];
    if (c >= 0) sum[size_t(c)] += x, cnt[size_t(c)] += 1.0;
  }
  if (n < 2)
    throw Error("sensor estimate: rows: the elevation histogram holds " + std::to_string(n) +
                " beam cluster(s); a range image needs at least 2 (give --sensor FILE)");
  Beams b;
  b.rows = n;
  for (int c = n - 1; c >= 0; --c) b.elevation_deg.push_back(sum[size_t(c)] / cnt[size_t(c)]);
  for (const auto& s : scans) {
    std::vector<int> beam(s.points.size(), -1);
    for (size_t i = 0; i < s.points.size(); ++i) {
      const double x = elevation_deg(s.points[i]);
      if (x >= lo && x <= hi + kBinDeg) beam[i] = cluster[bin_of(x)];
    }
    b.beam.push_back(std::move(beam));
  }
  return b;
}

}  // namespace

Beams find_beams(const std::vector<ScanSample>& scans) {
  bool rings = !scans.empty();
  for (const auto& s : scans) rings = rings && !s.ring.empty() && s.ring.size() == s.points.size();
  return rings ? beams_from_rings(scans) : beams_from_elevations(scans);
}

int estimate_width(const std::vector<ScanSample>& scans, const Beams& b) {
  std::vector<double> steps;
  for (size_t k = 0; k < scans.size(); ++k) {
    std::map<int, std::vector<double>> az;
    const auto& pts = scans[k].points;
    for (size_t i = 0; i < pts.size(); ++i)
      if (b.beam[k][i] >= 0 && range_m(pts[i]) > 0.0)
        az[b.beam[k][i]].push_back(std::atan2(double(pts[i].y), double(pts[i].x)) * 180.0 / M_PI);
    for (auto& [beam, a] : az) {
      std::sort(a.begin(), a.end());
      for (size_t i = 1; i < a.size(); ++i)
        if (a[i] - a[i - 1] > 1e-6) steps.push_back(a[i] - a[i - 1]);
    }
  }
  if (steps.empty()) throw Error("sensor estimate: width: no two points of one beam to measure the azimuth step");
  const double step = median(steps);
  return int(std::max(1L, std::lround(360.0 / step)));
}

}  // namespace sgnlf::detail
