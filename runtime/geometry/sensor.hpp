// A spinning LiDAR described as a range image (protocol §1–2).
#pragma once
#include <string>

#include "core/config_fwd.hpp"
#include "geometry/sweep_timing.hpp"

namespace sgnlf {

// Upper bound on height × width accepted by Sensor::validate().
constexpr long kMaxSensorPixels = 1L << 20;

struct Sensor {
  std::string name = "kitti360";
  int height = 66;          // beams (rows)
  int width = 1030;         // azimuth bins (columns)
  double fov_up_deg = 2.0;  // elevation of row 0
  double fov_deg = 26.9;    // total vertical field of view
  double max_range_m = 80.0;
  double min_range_m = 0.0;  // nuScenes drops returns ≤ 1.8 m
  double rate_hz = 10.0;
  // When each point of a sweep was measured (sweep_timing.hpp); a sweep lasts 1 / rate_hz.
  SweepTiming sweep;

  // A return at this range is a measurement of the scene: min_range_m < range < max_range_m
  // (returns within min_range_m are the vehicle itself, e.g. ~20 % of a nuScenes sweep). The
  // one rule for the range images and the points every method uses.
  bool in_range(double range) const {
    return range > min_range_m && range > 0.0 && range < max_range_m;
  }
  double sweep_duration_s() const { return 1.0 / rate_hz; }
  // The keys and ranges (core/config_fields.hpp); min_range_m's range [0, max_range_m] and the
  // pixel count are validate()'s. "sweep" is read and written by sensor_from_json /
  // sensor_to_json: its default and whether it is written depend on the name.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("name", s.name);
    v("height", s.height, 1, 4096);
    v("width", s.width, 1, 65536);
    v("fov_deg", s.fov_deg, 1e-3, 180.0);
    v("fov_up_deg", s.fov_up_deg, -90.0, 90.0);
    v("max_range_m", s.max_range_m, 1e-3, 1e4);
    v("min_range_m", s.min_range_m);
    v("rate_hz", s.rate_hz, 1e-3, 1e4);
  }
  void validate() const;
};

// The per-point time model of a named preset ("kitti360", "nuscenes"); the default for others.
SweepTiming preset_sweep_timing(const std::string& name);

// Built-in presets: "kitti360" (HDL-64E) and "nuscenes" (HDL-32E).
Sensor sensor_preset(const std::string& name);
// JSON: the keys of the struct; "sweep" {direction, start_azimuth_deg, reference} is optional
// and written only when it differs from preset_sweep_timing(name), so the sensor records
// written before the time model existed read and write back unchanged.
Sensor sensor_from_json(const Json& j, const std::string& where);
Json sensor_to_json(const Sensor& s);

}  // namespace sgnlf
