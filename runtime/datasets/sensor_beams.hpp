// The beams of a sample of scans (internal to sensor_estimate.cpp): from the ring field when
// the scans carry one, else from the peaks of the elevation histogram; each point tagged with
// its beam so that the azimuth step can be measured within one beam.
#pragma once
#include <cmath>
#include <vector>

#include "datasets/sensor_estimate.hpp"

namespace sgnlf::detail {

// Points this close to the sensor are left out of the elevation statistics: a real head's
// lasers sit a few centimetres off its axis, which bends the elevation of near returns.
constexpr double kNearM = 3.0;

struct Beams {
  bool from_rings = false;
  int rows = 0;                          // beam count (ring span, or histogram peaks)
  std::vector<double> elevation_deg;     // per beam found, top first
  std::vector<std::vector<int>> beam;    // per scan, per point: beam index, −1 = none
};

inline double elevation_deg(const PointXYZI& p) {
  return std::atan2(double(p.z), std::sqrt(double(p.x) * p.x + double(p.y) * p.y)) * 180.0 / M_PI;
}
inline double range_m(const PointXYZI& p) {
  return std::sqrt(double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z);
}

// Throws Error ("rows: ...") when fewer than two beams are found.
Beams find_beams(const std::vector<ScanSample>& scans);

// 360° over the median azimuth step between neighbouring points of one beam in one scan.
int estimate_width(const std::vector<ScanSample>& scans, const Beams& b);

}  // namespace sgnlf::detail
