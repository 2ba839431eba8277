// When each point of a spinning LiDAR's sweep was measured: the per-point time model of a
// sensor (a property of the sensor preset, geometry/sensor.hpp). A sweep lasts 1 / rate_hz
// (nuScenes' HDL-32E at 20 Hz: 50 ms; KITTI's HDL-64E at 10 Hz: 100 ms) and the head turns at a
// constant rate, so a point's time follows from its azimuth β = atan2(y, x) in the LiDAR frame:
//   fraction f = ((direction · (β − β_start)) mod 2π) / 2π ∈ [0, 1),
//   time offset from the frame's timestamp τ = (f − reference) · duration.
// The frame's timestamp and pose hold at `reference` (0: sweep start, 0.5: middle, 1: end).
#pragma once
#include <string>

#include "core/config_fwd.hpp"
#include "geometry/se3.hpp"

namespace sgnlf {

struct SweepTiming {
  // −1: clockwise seen from above (azimuth decreasing over the sweep, Velodyne's spin), +1:
  // counter-clockwise.
  int direction = -1;
  // Azimuth (degrees, LiDAR frame, atan2(y, x)) where a sweep starts and the previous ends.
  double start_azimuth_deg = 180.0;
  // Fraction of the sweep at which the frame's timestamp and pose hold.
  double reference = 0.5;

  // The keys and ranges (core/config_fields.hpp); direction's two values are validate()'s.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("direction", s.direction);
    v("start_azimuth_deg", s.start_azimuth_deg, -360.0, 360.0);
    v("reference", s.reference, 0.0, 1.0);
  }

  void validate(const std::string& where) const;
  bool operator==(const SweepTiming& o) const {
    return direction == o.direction && start_azimuth_deg == o.start_azimuth_deg && reference == o.reference;
  }
  bool operator!=(const SweepTiming& o) const { return !(*this == o); }
};

// Fraction of the sweep, in [0, 1), at which the ray through p_lidar was fired.
double sweep_fraction(const SweepTiming& timing, const Vec3& p_lidar);
// Time of that ray relative to the frame's timestamp (seconds): (fraction − reference) · duration.
double sweep_time_offset(const SweepTiming& timing, double duration_s, const Vec3& p_lidar);

SweepTiming sweep_timing_from_json(ConfigReader& r);  // keys as in to_json; errors name r.where()
Json sweep_timing_to_json(const SweepTiming& t);

}  // namespace sgnlf
