// Which device a result ran on, and per-device baselines of the smoke tables. A smoke table (a
// few dozen steps of an untrained model) is compared tightly only as a deterministic twin: same
// OpenCL device, driver and device profile. A device whose rounding differs (a GPU, another
// vendor) gets its own baseline beside the committed one,
//   results/tables/<table>/smoke/devices/<device slug>/results.json
// (a copy of that device's smoke run: results/README.md), and `sgnlf compare` takes it instead
// of the committed one when the new result ran on that device; without one it compares loosely
// and says so (harness/compare.hpp).
#pragma once
#include <string>

#include "core/config.hpp"

namespace sgnlf::harness {

// Same OpenCL device (context.opencl.device), driver (.driver_version) and device profile
// (context.device_profile.name; a result without one, made before profiles were recorded,
// matches any).
bool same_device(const Json& a, const Json& b);
// Whether the two results ran on different profiles (both recorded, names differ).
bool different_profile(const Json& a, const Json& b);

// A file-name-safe name of a result's device, driver and profile: lower-case letters, digits
// and dots, other runs of characters as '-', the three parts joined by '_', e.g.
// "pthread-skylake-avx512-amd-epyc_3.1-debian_cpu" (no profile part when none is recorded).
std::string device_slug(const Json& results);

// Where the baseline of `fresh`'s device sits beside the committed `baseline_path`:
// <dir of baseline_path>/devices/<device_slug(fresh)>/results.json.
std::string device_baseline_path(const std::string& baseline_path, const Json& fresh);

// The baseline to compare `fresh` with: the committed one (`baseline_path`, already read into
// `baseline`), or, for a smoke table that `fresh` ran on another device, that device's own
// baseline when the file exists. `looked_for` is the per-device path when one was looked for.
struct BaselineChoice {
  std::string path;
  Json baseline;
  bool per_device = false;
  std::string looked_for;
};
BaselineChoice choose_baseline(const std::string& baseline_path, const Json& baseline,
                               const Json& fresh);

}  // namespace sgnlf::harness
