// A single scan file or a plain folder of scans: no poses, no clock, and a sensor that is
// given (--sensor), else estimated from the scans (sensor_estimate.hpp) and replaced by the
// preset it matches, if any (so folders of KITTI or nuScenes scans keep their presets).
#include <algorithm>
#include <filesystem>

#include "core/error.hpp"
#include "core/log.hpp"
#include "datasets/loader_internal.hpp"
#include "datasets/sensor_estimate.hpp"
#include "io/scan_io.hpp"

namespace sgnlf::detail {
namespace fs = std::filesystem;

Sensor plain_scans_sensor(const std::vector<std::string>& files, const LoadOptions& opt) {
  Sensor s;
  if (!opt.sensor.empty()) {
    s = resolve_sensor(opt, s);
  } else {
    SensorEstimateOptions eo;
    if (opt.rate_hz > 0.0) eo.rate_hz = opt.rate_hz;
    const SensorEstimate e = estimate_sensor(read_scan_sample(files), eo);
    const std::string preset = matching_preset(e.sensor);
    if (preset.empty()) {
      s = e.sensor;
      log::info("plain scans: no sensor given; using the estimated one (", s.height, "x", s.width,
                "; give --sensor NAME|FILE to choose another)");
    } else {
      s = sensor_preset(preset);
      log::info("plain scans: no sensor given; the estimate (", e.sensor.height, "x", e.sensor.width,
                ", fov_up ", e.sensor.fov_up_deg, "°, fov ", e.sensor.fov_deg, "°) matches the preset ",
                preset, ", used instead");
    }
  }
  if (opt.rate_hz > 0.0) s.rate_hz = opt.rate_hz;
  return s;
}

Dataset load_scans(const std::string& path, const LoadOptions& opt) {
  std::vector<std::string> files;
  if (fs::is_regular_file(path)) {
    files.push_back(path);
  } else {
    for (const auto& e : fs::directory_iterator(path))
      if (e.is_regular_file() && io::is_scan_file(e.path().string())) files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
  }
  const Sensor sensor = plain_scans_sensor(files, opt);
  Dataset d;
  d.name = fs::path(path).filename().string();
  d.source = "scans";
  d.path = path;
  d.frequency = resolve_frequency(opt, "standard");
  d.sensor = sensor;
  ProjectionStats dropped;
  const size_t first = size_t(std::max(0, opt.start));
  const size_t stride = size_t(opt.stride > 0 ? opt.stride : 1);
  for (size_t i = first; i < files.size() && (opt.frames < 0 || int(d.frames.size()) < opt.frames); i += stride) {
    Frame f;
    f.id = int(i);
    f.timestamp_s = double(i) / sensor.rate_hz;  // no pose and no clock: identity poses
    load_frame_scan(f, files[i], sensor, opt.load_points, dropped);
    d.frames.push_back(std::move(f));
  }
  log::warn(path, ": plain scans carry no poses; ground-truth poses are the identity");
  finish_dataset(d, dropped);
  return d;
}

}  // namespace sgnlf::detail
