// OpenCL platform/device discovery and run-time selection (--device or SGNLF_DEVICE).
#pragma once
#include <string>
#include <vector>

#include "cl/error.hpp"

namespace sgnlf::cl {

struct DeviceInfo {
  int index = 0;  // global index over all platforms, as printed by `sgnlf devices`
  int platform_index = 0;
  cl_platform_id platform = nullptr;
  cl_device_id id = nullptr;
  std::string platform_name, platform_vendor, platform_version;
  std::string name, vendor, version, driver_version, opencl_c_version, type;
  unsigned compute_units = 0;
  unsigned clock_mhz = 0;
  unsigned long long global_mem_bytes = 0, local_mem_bytes = 0, max_alloc_bytes = 0;
  size_t max_work_group_size = 0;
  bool local_mem_is_global = false;
  bool fp16 = false, fp64 = false;
  std::string extensions;

  std::string describe() const;  // "[0] Portable Computing Language / pthread-... (CPU)"
};

// Every device of every platform. Throws DeviceError when no platform exists, with the
// instructions to install PoCL.
std::vector<DeviceInfo> list_devices();

// Selects a device by spec: "" means SGNLF_DEVICE if set, else the first GPU, else device 0.
// A spec is a global index or a case-insensitive substring of the platform or device name.
// When nothing matches, the DeviceError lists every device found.
DeviceInfo select_device(const std::string& spec = "");

// The spec in effect when none is given explicitly (SGNLF_DEVICE or "").
std::string default_device_spec();

// True when at least one OpenCL platform with a device exists (tests use it to skip).
bool any_device_available();

}  // namespace sgnlf::cl
