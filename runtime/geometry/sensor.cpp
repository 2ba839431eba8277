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
}

Sensor sensor_preset(const std::string& name) {
  Sensor s;
  if (name == "kitti360") {
    s = Sensor{"kitti360", 66, 1030, 2.0, 26.9, 80.0, 0.0, 10.0};
  } else if (name == "nuscenes") {
    s = Sensor{"nuscenes", 32, 1080, 10.0, 40.0, 80.0, 1.8, 20.0};
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
  r.finish();
  s.validate();
  return s;
}

Json sensor_to_json(const Sensor& s) {
  return Json{{"name", s.name},           {"height", s.height},
              {"width", s.width},         {"fov_up_deg", s.fov_up_deg},
              {"fov_deg", s.fov_deg},     {"max_range_m", s.max_range_m},
              {"min_range_m", s.min_range_m}, {"rate_hz", s.rate_hz}};
}

}  // namespace sgnlf
