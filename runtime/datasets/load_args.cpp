// Command-line load options (see load_args.hpp).
#include "datasets/load_args.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "core/config.hpp"
#include "core/error.hpp"
#include "geometry/sensor.hpp"

namespace sgnlf {

std::string frequency_class(double rate_hz) { return rate_hz <= kLowFrequencyMaxHz ? "low" : "standard"; }

void set_frequency_arg(LoadOptions& opt, const std::string& value) {
  if (value == "standard" || value == "low") {
    opt.frequency = value;
    return;
  }
  const std::string what = "--frequency '" + value + "': ";
  const char* b = value.c_str();
  char* end = nullptr;
  errno = 0;
  const double hz = std::strtod(b, &end);
  if (value.empty() || end == b || *end != '\0' || errno != 0)
    throw ConfigError(what + "expected standard, low or a scan rate in Hz (e.g. 10, or 2 for nuScenes keyframes)");
  if (!std::isfinite(hz) || hz <= 0.0 || hz > 1e4)
    throw ConfigError(what + "a scan rate must be > 0 and <= 10000 Hz");
  opt.rate_hz = hz;
}

void set_sensor_arg(LoadOptions& opt, const std::string& value) {
  const std::string what = "--sensor '" + value + "': ";
  if (value.empty()) throw ConfigError(what + "empty (a preset name: kitti360, nuscenes, or a sensor JSON file)");
  try {
    if (std::filesystem::is_regular_file(value))
      (void)sensor_from_json(load_json_file(value), value);
    else if (std::filesystem::exists(value))
      throw ConfigError("not a file");
    else
      (void)sensor_preset(value);
  } catch (const Error& e) {
    throw ConfigError(what + e.what() + " (a preset name: kitti360, nuscenes, or a sensor JSON file)");
  }
  opt.sensor = value;
}

}  // namespace sgnlf
