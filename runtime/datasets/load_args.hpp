// The command-line spellings of the load options every data-loading command shares
// (`--sensor NAME|FILE`, `--frequency standard|low|HZ`), parsed into LoadOptions with errors
// that name the option and the value.
#pragma once
#include <string>

#include "datasets/loader.hpp"

namespace sgnlf {

// Scans at this rate or below follow the protocol's low-frequency rules (protocol §3: the
// 2 Hz windows of 36 frames, test frames 4, 12, 20); above it the standard ones (10 Hz, 64).
constexpr double kLowFrequencyMaxHz = 5.0;

// "low" for rate_hz <= kLowFrequencyMaxHz, else "standard".
std::string frequency_class(double rate_hz);

// `--frequency`: "standard" or "low" (the class, as before), or a scan rate in Hz
// (0 < HZ <= 10000, e.g. "2" for nuScenes keyframes) that sets opt.rate_hz and, through it,
// the class. ConfigError "--frequency 'VALUE': ..." otherwise.
void set_frequency_arg(LoadOptions& opt, const std::string& value);

// `--sensor`: a preset name (kitti360, nuscenes) or a sensor JSON file, read and validated
// now so that a typo fails before any data is read. ConfigError "--sensor 'VALUE': ..." otherwise.
void set_sensor_arg(LoadOptions& opt, const std::string& value);

}  // namespace sgnlf
