// A single scan file or a plain folder of scans: no poses (Dataset::has_reference_poses false),
// times from a times.txt or the file names when they have them (scan_times.hpp; they also set
// the frequency class), and a sensor that is given (--sensor), else estimated from the scans
// (sensor_estimate.hpp) and replaced by the preset it matches, if any (so folders of KITTI or
// nuScenes scans keep their presets).
#include <algorithm>
#include <filesystem>
#include <optional>

#include "core/error.hpp"
#include "core/log.hpp"
#include "datasets/load_args.hpp"
#include "datasets/loader_internal.hpp"
#include "datasets/scan_times.hpp"
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

float plain_scans_intensity_scale(const std::vector<std::string>& files) {
  float top = 0.0f;
  for (const auto& sc : read_scan_sample(files))
    for (const auto& p : sc.points) top = std::max(top, p.intensity);
  if (top <= 1.0f) return 1.0f;
  if (top <= 255.0f) return 1.0f / 255.0f;
  if (top <= 65535.0f) return 1.0f / 65535.0f;
  log::warn("plain scans: intensities up to ", top, "; scaled by 1/", top, " into [0, 1]");
  return 1.0f / top;
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
  const float intensity_scale = files.empty() ? 1.0f : plain_scans_intensity_scale(files);
  if (intensity_scale != 1.0f)
    log::info(path, ": intensities scaled by ", intensity_scale, " into [0, 1]");
  // The scans' times (times.txt or the file names), else one sweep per 1 / rate_hz.
  const std::optional<ScanTimes> times =
      fs::is_directory(path) ? scan_times(path, files) : std::nullopt;
  Dataset d;
  d.name = fs::path(path).filename().string();
  d.source = "scans";
  d.has_reference_poses = false;
  d.path = path;
  std::string measured;  // the frequency class of the times found, when no rate was asked for
  if (times && opt.rate_hz <= 0.0 && times->rate_hz() > 0.0) {
    measured = frequency_class(times->rate_hz());
    log::info(path, ": scan times from ", times->source, ", ", times->rate_hz(), " Hz (", measured,
              " frequency)");
  }
  d.frequency = resolve_frequency(opt, measured.empty() ? "standard" : measured);
  d.sensor = sensor;
  ProjectionStats dropped;
  const size_t first = size_t(std::max(0, opt.start));
  const size_t stride = size_t(opt.stride > 0 ? opt.stride : 1);
  for (size_t i = first; i < files.size() && (opt.frames < 0 || int(d.frames.size()) < opt.frames); i += stride) {
    Frame f;
    f.id = int(i);
    f.timestamp_s = times ? times->seconds[i] : double(i) / sensor.rate_hz;  // identity poses
    load_frame_scan(f, files[i], sensor, opt.load_points, dropped, "", intensity_scale);
    d.frames.push_back(std::move(f));
  }
  log::info(path, ": plain scans carry no poses: nothing is scored against reference poses");
  finish_dataset(d, dropped);
  return d;
}

}  // namespace sgnlf::detail
