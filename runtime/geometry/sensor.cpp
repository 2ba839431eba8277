#include "geometry/sensor.hpp"

#include "core/config.hpp"
#include "core/config_fields.hpp"

namespace sgnlf {

void Sensor::validate() const {
  const std::string w = "sensor '" + name + "'";
  config::check_fields(*this, w);
  // Every frame holds range, intensity and mask images of height × width floats, and training
  // keeps all frames: 4096 × 65536 was 3 GB per frame. 2^20 pixels (12 MB a frame) is over
  // three times the densest spinning LiDAR made (128 beams × 2048 columns).
  if (long(height) * long(width) > kMaxSensorPixels)
    throw ConfigError(w + ": height × width = " + std::to_string(long(height) * long(width)) +
                      " pixels per range image, more than " + std::to_string(kMaxSensorPixels) +
                      " (height " + std::to_string(height) + ", width " + std::to_string(width) + ")");
  check_range(w, "min_range_m", min_range_m, 0.0, max_range_m);
  sweep.validate(w + ": sweep");
}

SweepTiming preset_sweep_timing(const std::string& name) {
  SweepTiming t;  // Velodyne heads spin clockwise seen from above
  if (name == "kitti360") {
    // KITTI: a sweep starts and ends behind the car (azimuth ±180°) and its timestamp is when
    // the head faces forward, mid-sweep (KISS-ICP's KITTI time model: t = 0.5 (−atan2(y, x)/π + 1)).
    t = SweepTiming{-1, 180.0, 0.5};
  } else if (name == "nuscenes") {
    // nuScenes LIDAR_TOP: the timestamp is when the full rotation is achieved (end of the sweep);
    // the points of a .pcd.bin are stored in firing order, and in scene-0916 the first column
    // lies at azimuth ≈ 180° of the LiDAR frame (x right, y forward: the car's left), the order
    // turning clockwise (measured: datasets/README.md "Sweep timing").
    t = SweepTiming{-1, 180.0, 1.0};
  }
  return t;
}

Sensor sensor_preset(const std::string& name) {
  Sensor s;
  if (name == "kitti360") {
    s = Sensor{"kitti360", 66, 1030, 2.0, 26.9, 80.0, 0.0, 10.0, preset_sweep_timing("kitti360")};
  } else if (name == "nuscenes") {
    s = Sensor{"nuscenes", 32, 1080, 10.0, 40.0, 80.0, 1.8, 20.0, preset_sweep_timing("nuscenes")};
  } else {
    throw ConfigError("unknown sensor preset '" + name + "' (known: kitti360, nuscenes)");
  }
  return s;
}

Sensor sensor_from_json(const Json& j, const std::string& where) {
  Sensor s;
  ConfigReader r(j, where);
  if (r.has("preset")) {
    std::string preset;
    r.get("preset", preset);
    s = sensor_preset(preset);
  }
  config::read_fields_here(r, s);
  if (r.has("sweep")) {
    ConfigReader rs = r.child("sweep");
    s.sweep = sweep_timing_from_json(rs);
  } else if (!r.has("preset")) {
    s.sweep = preset_sweep_timing(s.name);
  }
  r.finish();
  s.validate();
  return s;
}

Json sensor_to_json(const Sensor& s) {
  Json j = config::write_fields(s);
  if (s.sweep != preset_sweep_timing(s.name)) j["sweep"] = sweep_timing_to_json(s.sweep);
  return j;
}

}  // namespace sgnlf
