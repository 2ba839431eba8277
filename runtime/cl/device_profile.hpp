// Device profiles: the launch shapes and kernel variants a device runs, as one table.
//
// A profile names the work-group size of the element-wise kernels (cl::launch_1d), the
// variant of the encoders' parameter backward (hash grid, time hash grid, K-Planes) and the
// points per work-item of the encoders' forward on CPUs. The built-in "cpu" profile is exactly
// what every run did before profiles existed (local size 64, the serial per-level backward,
// hash-grid chunks of 256 points, plane chunks of 64); "gpu" keeps local size 64, runs one point
// per work-item and the deterministic parallel backward (sorted by entry, summed in point order,
// bit-identical to the serial one: docs/architecture.md). A device of type CPU gets "cpu", any
// other device (GPU, accelerator) "gpu"; the vendor is recorded in the result's context but
// chooses nothing yet. `--device-profile cpu|gpu|auto|FILE` (or SGNLF_DEVICE_PROFILE) overrides
// the choice; FILE is JSON whose keys are read over the built-in profile named by its "base"
// (default: the device's automatic one), unknown keys refused.
#pragma once
#include <string>

#include "cl/device.hpp"
#include "core/config_choices.hpp"
#include "core/config_fwd.hpp"

namespace sgnlf::cl {

// The encoders' parameter backward: serial = one work-item per level (or scale-group) owning its
// slice, summing over the points in order; atomic = one work-item per (point, level) with
// compare-and-swap float adds (order varies between runs); deterministic_parallel = the
// (entry, point) contributions sorted by entry (stable radix sort) and summed per entry in the
// serial order, one work-item per entry.
enum class EncoderBackward { Serial, Atomic, DeterministicParallel };

inline constexpr std::pair<EncoderBackward, const char*> kEncoderBackwardNames[] = {
    {EncoderBackward::Serial, "serial"},
    {EncoderBackward::Atomic, "atomic"},
    {EncoderBackward::DeterministicParallel, "deterministic_parallel"}};

const char* encoder_backward_name(EncoderBackward b);

struct DeviceProfile {
  std::string name = "cpu";
  // Work-group size of the 1-D element-wise kernels (global size rounded up to it).
  int local_size = 64;
  EncoderBackward encoder_backward = EncoderBackward::Serial;
  // Points per work-item of the hash grid's forward and d_x under schedule "auto"
  // (kernels/field/hashgrid.cl CHUNK; 1 = the per-point kernels).
  int hash_grid_chunk = 256;
  // Points per work-item of the time hash grid's and K-Planes' forward when their config's
  // chunk is 0 (1 = one point per work-item, work-groups of 64).
  int plane_chunk = 64;

  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("name", s.name);
    v("local_size", s.local_size, 1, 1024);
    v("encoder_backward", s.encoder_backward, config::choices(kEncoderBackwardNames));
    v("hash_grid_chunk", s.hash_grid_chunk, 1, 65536);
    v("plane_chunk", s.plane_chunk, 1, 65536);
  }
  // Throws ConfigError naming `where` and the key.
  void validate(const std::string& where = "device_profile") const;
  Json to_json() const;
  // Strict: unknown keys refused. `base` is the profile the keys are read over (a "base" key in
  // the JSON, "cpu" or "gpu", replaces it).
  static DeviceProfile from_json(const Json& j, const std::string& where,
                                 const DeviceProfile& base);
  bool operator==(const DeviceProfile& o) const;
};

DeviceProfile cpu_profile();
DeviceProfile gpu_profile();
// "cpu" for a device of type CPU, "gpu" for any other.
DeviceProfile automatic_profile(const DeviceInfo& device);
// spec "" = default_profile_spec(); "auto" = automatic_profile(device); "cpu", "gpu"; anything
// else is the path of a JSON profile file. Throws ConfigError naming the spec or the file.
DeviceProfile resolve_profile(const std::string& spec, const DeviceInfo& device);
// The spec in effect when none is given explicitly (SGNLF_DEVICE_PROFILE or "auto").
std::string default_profile_spec();

}  // namespace sgnlf::cl
