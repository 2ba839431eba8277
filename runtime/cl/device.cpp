#include "cl/device.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>

namespace sgnlf::cl {
namespace {

std::string platform_str(cl_platform_id p, cl_platform_info what) {
  size_t n = 0;
  check(clGetPlatformInfo(p, what, 0, nullptr, &n), "clGetPlatformInfo");
  std::string s(n, '\0');
  check(clGetPlatformInfo(p, what, n, s.data(), nullptr), "clGetPlatformInfo");
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

std::string device_str(cl_device_id d, cl_device_info what) {
  size_t n = 0;
  check(clGetDeviceInfo(d, what, 0, nullptr, &n), "clGetDeviceInfo");
  std::string s(n, '\0');
  check(clGetDeviceInfo(d, what, n, s.data(), nullptr), "clGetDeviceInfo");
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

template <typename T>
T device_val(cl_device_id d, cl_device_info what) {
  T v{};
  check(clGetDeviceInfo(d, what, sizeof(T), &v, nullptr), "clGetDeviceInfo");
  return v;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

const char* kInstallHint =
    "no OpenCL platform found. Install a CPU OpenCL driver with "
    "'apt-get install pocl-opencl-icd ocl-icd-libopencl1' (or run scripts/setup.sh), "
    "or the vendor driver of your GPU; 'clinfo -l' must list a device.";

std::vector<cl_platform_id> platforms() {
  cl_uint n = 0;
  const cl_int rc = clGetPlatformIDs(0, nullptr, &n);
  if (rc == -1001 /* CL_PLATFORM_NOT_FOUND_KHR */ || (rc == CL_SUCCESS && n == 0)) return {};
  check(rc, "clGetPlatformIDs");
  std::vector<cl_platform_id> ids(n);
  check(clGetPlatformIDs(n, ids.data(), nullptr), "clGetPlatformIDs");
  return ids;
}

}  // namespace

std::string DeviceInfo::describe() const {
  return "[" + std::to_string(index) + "] " + platform_name + " / " + name + " (" + type + ")";
}

std::vector<DeviceInfo> list_devices() {
  const auto plats = platforms();
  if (plats.empty()) throw DeviceError(kInstallHint);
  std::vector<DeviceInfo> out;
  for (size_t pi = 0; pi < plats.size(); ++pi) {
    cl_uint nd = 0;
    const cl_int rc = clGetDeviceIDs(plats[pi], CL_DEVICE_TYPE_ALL, 0, nullptr, &nd);
    if (rc == CL_DEVICE_NOT_FOUND || nd == 0) continue;
    check(rc, "clGetDeviceIDs");
    std::vector<cl_device_id> devs(nd);
    check(clGetDeviceIDs(plats[pi], CL_DEVICE_TYPE_ALL, nd, devs.data(), nullptr),
          "clGetDeviceIDs");
    for (cl_device_id d : devs) {
      DeviceInfo info;
      info.index = int(out.size());
      info.platform_index = int(pi);
      info.platform = plats[pi];
      info.id = d;
      info.platform_name = platform_str(plats[pi], CL_PLATFORM_NAME);
      info.platform_vendor = platform_str(plats[pi], CL_PLATFORM_VENDOR);
      info.platform_version = platform_str(plats[pi], CL_PLATFORM_VERSION);
      info.name = device_str(d, CL_DEVICE_NAME);
      info.vendor = device_str(d, CL_DEVICE_VENDOR);
      info.version = device_str(d, CL_DEVICE_VERSION);
      info.driver_version = device_str(d, CL_DRIVER_VERSION);
      info.opencl_c_version = device_str(d, CL_DEVICE_OPENCL_C_VERSION);
      const auto type = device_val<cl_device_type>(d, CL_DEVICE_TYPE);
      info.type = (type & CL_DEVICE_TYPE_GPU)           ? "GPU"
                  : (type & CL_DEVICE_TYPE_CPU)         ? "CPU"
                  : (type & CL_DEVICE_TYPE_ACCELERATOR) ? "accelerator"
                                                        : "other";
      info.compute_units = device_val<cl_uint>(d, CL_DEVICE_MAX_COMPUTE_UNITS);
      info.clock_mhz = device_val<cl_uint>(d, CL_DEVICE_MAX_CLOCK_FREQUENCY);
      info.global_mem_bytes = device_val<cl_ulong>(d, CL_DEVICE_GLOBAL_MEM_SIZE);
      info.local_mem_bytes = device_val<cl_ulong>(d, CL_DEVICE_LOCAL_MEM_SIZE);
      info.max_alloc_bytes = device_val<cl_ulong>(d, CL_DEVICE_MAX_MEM_ALLOC_SIZE);
      info.max_work_group_size = device_val<size_t>(d, CL_DEVICE_MAX_WORK_GROUP_SIZE);
      info.local_mem_is_global =
          device_val<cl_device_local_mem_type>(d, CL_DEVICE_LOCAL_MEM_TYPE) == CL_GLOBAL;
      info.extensions = device_str(d, CL_DEVICE_EXTENSIONS);
      info.fp16 = info.extensions.find("cl_khr_fp16") != std::string::npos;
      info.fp64 = info.extensions.find("cl_khr_fp64") != std::string::npos;
      out.push_back(std::move(info));
    }
  }
  if (out.empty()) throw DeviceError(kInstallHint);
  return out;
}

std::string default_device_spec() {
  const char* e = std::getenv("SGNLF_DEVICE");
  return e ? std::string(e) : std::string();
}

DeviceInfo select_device(const std::string& spec_in) {
  const std::string spec = spec_in.empty() ? default_device_spec() : spec_in;
  const auto devices = list_devices();
  if (spec.empty()) {
    for (const auto& d : devices)
      if (d.type == "GPU") return d;
    return devices.front();
  }
  const bool numeric =
      std::all_of(spec.begin(), spec.end(), [](unsigned char c) { return std::isdigit(c); });
  if (numeric) {
    const long idx = std::strtol(spec.c_str(), nullptr, 10);
    if (idx >= 0 && idx < long(devices.size())) return devices[size_t(idx)];
  } else {
    const std::string want = lower(spec);
    for (const auto& d : devices) {
      if (lower(d.name).find(want) != std::string::npos ||
          lower(d.platform_name).find(want) != std::string::npos)
        return d;
    }
  }
  std::string msg = "no OpenCL device matches '" + spec +
                    "' (an index or a case-insensitive substring of the platform or device "
                    "name); devices found:";
  for (const auto& d : devices) msg += "\n  " + d.describe();
  throw DeviceError(msg);
}

bool any_device_available() {
  try {
    return !list_devices().empty();
  } catch (const DeviceError&) {
    return false;
  }
}

}  // namespace sgnlf::cl
