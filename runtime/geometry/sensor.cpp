#include "geometry/sensor.hpp"

namespace sgnlf {

void Sensor::validate() const {
  const std::string w = "sensor '" + name + "'";
  check_range(w, "height", height, 1, 4096);
  check_range(w, "width", width, 1, 65536);
  // Every frame holds range, intensity and mask images of height × width floats, and training
  // keeps all frames: 4096 × 65536 was 3 GB per frame. 2^20 pixels (12 MB a frame) is over
  // three times the densest spinning LiDAR made (128 beams × 2048 columns).
  if (long(height) * long(width) > kMaxSensorPixels)
    throw ConfigError(w + ": height × width = " + std::to_string(long(height) * long(width)) +
                      " pixels per range image, more than " + std::to_string(kMaxSensorPixels) +
                      " (height " + std::to_string(height) + ", width " + std::to_string(width) + ")");
  check_range(w, "fov_deg", fov_deg, 1e-3, 180.0);
  check_range(w, "fov_up_deg", fov_up_deg, -90.0, 90.0);
  check_range(w, "max_range_m", max_range_m, 1e-3, 1e4);
  check_range(w, "min_range_m", min_range_m, 0.0, max_range_m);
  check_range(w, "rate_hz", rate_hz, 1e-3, 1e4);
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
  r.get("name", s.name)
      .get("height", s.height)
      .get("width", s.width)
      .get("fov_up_deg", s.fov_up_deg)
      .get("fov_deg", s.fov_deg)
      .get("max_range_m", s.max_range_m)
      .get("min_range_m", s.min_range_m)
      .get("rate_hz", s.rate_hz);
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
  Json j{{"name", s.name},           {"height", s.height},
         {"width", s.width},         {"fov_up_deg", s.fov_up_deg},
         {"fov_deg", s.fov_deg},     {"max_range_m", s.max_range_m},
         {"min_range_m", s.min_range_m}, {"rate_hz", s.rate_hz}};
  if (s.sweep != preset_sweep_timing(s.name)) j["sweep"] = sweep_timing_to_json(s.sweep);
  return j;
}

}  // namespace sgnlf
