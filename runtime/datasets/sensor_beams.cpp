// Beams and azimuth resolution of a scan sample (see sensor_beams.hpp).
#include "datasets/sensor_beams.hpp"

#include <algorithm>
#include <map>

#include "core/error.hpp"

namespace sgnlf::detail {
namespace {

constexpr double kBinDeg = 0.02;     // elevation histogram bin
constexpr long kSmoothBins = 3;      // ±0.06° box smoothing
constexpr long kPeakBins = 10;       // peaks at least 0.2° apart
constexpr double kMinPeakShare = 0.1;

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
  const long nbins = long((hi - lo) / kBinDeg) + 1;
  auto bin_of = [&](double x) { return std::clamp(long((x - lo) / kBinDeg), 0L, nbins - 1); };
  std::vector<double> count(size_t(nbins), 0.0), smooth(size_t(nbins), 0.0);
  for (double x : e) count[size_t(bin_of(x))] += 1.0;
  // Beams are the peaks of the histogram smoothed over ±kSmoothBins: real heads smear each
  // laser over ~0.2° (per-laser offsets, motion compensation), so the gaps between neighbouring
  // beams fill up and only the peaks remain. A peak is the largest value within ±kPeakBins
  // (beams at least 0.2° apart) and at least kMinPeakShare of the median peak.
  for (long k = 0; k < nbins; ++k)
    for (long q = std::max(0L, k - kSmoothBins); q <= std::min(nbins - 1, k + kSmoothBins); ++q)
      smooth[size_t(k)] += count[size_t(q)];
  std::vector<long> peaks;
  for (long k = 0; k < nbins; ++k) {
    if (smooth[size_t(k)] <= 0.0 || (k > 0 && smooth[size_t(k)] <= smooth[size_t(k - 1)])) continue;
    long end = k;  // a flat top (one exact beam, smoothed) is judged from its middle
    while (end + 1 < nbins && smooth[size_t(end + 1)] == smooth[size_t(k)]) ++end;
    const long c = (k + end) / 2;
    bool top = true;
    for (long q = std::max(0L, c - kPeakBins); top && q <= std::min(nbins - 1, c + kPeakBins); ++q)
      top = smooth[size_t(q)] <= smooth[size_t(k)];
    if (top) peaks.push_back(c);
  }
  std::vector<double> heights;
  for (long k : peaks) heights.push_back(smooth[size_t(k)]);
  const double min_height = kMinPeakShare * median(heights);
  peaks.erase(std::remove_if(peaks.begin(), peaks.end(), [&](long k) { return smooth[size_t(k)] < min_height; }),
              peaks.end());
  if (peaks.size() < 2)
    throw Error("sensor estimate: rows: the elevation histogram holds " + std::to_string(peaks.size()) +
                " beam peak(s); a range image needs at least 2 (give --sensor FILE)");
  // Each beam's elevation: the mean of the raw elevations within ±kPeakBins / 2 of its peak
  // (the smoothing window's plateau would shift an exact beam by up to kSmoothBins bins).
  const size_t n = peaks.size();
  std::vector<double> sum(n, 0.0), cnt(n, 0.0);
  std::vector<long> owner(size_t(nbins), -1);  // the peak owning each bin: the nearest one
  for (long k = 0, p = 0; k < nbins; ++k) {
    while (p + 1 < long(n) && std::abs(peaks[size_t(p + 1)] - k) < std::abs(peaks[size_t(p)] - k)) ++p;
    owner[size_t(k)] = p;
  }
  for (double x : e) {
    const long k = bin_of(x), p = owner[size_t(k)];
    if (std::abs(k - peaks[size_t(p)]) <= kPeakBins / 2) sum[size_t(p)] += x, cnt[size_t(p)] += 1.0;
  }
  Beams b;
  b.rows = int(n);
  for (size_t p = n; p-- > 0;) b.elevation_deg.push_back(sum[p] / cnt[p]);
  // Points join the beam of their bin's peak when within ±kPeakBins / 2 of it (the core of the
  // beam, so that the azimuth steps are measured within one laser).
  for (const auto& s : scans) {
    std::vector<int> beam(s.points.size(), -1);
    for (size_t i = 0; i < s.points.size(); ++i) {
      const double x = elevation_deg(s.points[i]);
      if (x < lo || x > hi) continue;
      const long k = bin_of(x), p = owner[size_t(k)];
      if (std::abs(k - peaks[size_t(p)]) <= kPeakBins / 2) beam[i] = int(p);
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
