#include "cl/runtime.hpp"

#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <vector>

#include "cl/kernel_sources.hpp"
#include "core/config.hpp"
#include "core/log.hpp"

namespace sgnlf::cl {

Runtime::Runtime(const std::string& spec, const std::string& profile_spec)
    : device_(select_device(spec)), device_profile_(resolve_profile(profile_spec, device_)) {
  open();
}
Runtime::Runtime(const DeviceInfo& device, const std::string& profile_spec)
    : device_(device), device_profile_(resolve_profile(profile_spec, device_)) {
  open();
}

void Runtime::set_device_profile(const DeviceProfile& p) {
  p.validate("Runtime::set_device_profile");
  device_profile_ = p;
}

void Runtime::open() {
  cl_int rc = CL_SUCCESS;
  cl_context_properties props[] = {CL_CONTEXT_PLATFORM,
                                   reinterpret_cast<cl_context_properties>(device_.platform), 0};
  cl_device_id dev = device_.id;
  cl_context ctx = clCreateContext(props, 1, &dev, nullptr, nullptr, &rc);
  check(rc, "clCreateContext", device_.describe());
  context_ = ContextHandle(ctx);
  cl_command_queue q = clCreateCommandQueue(ctx, dev, CL_QUEUE_PROFILING_ENABLE, &rc);
  check(rc, "clCreateCommandQueue", device_.describe());
  queue_ = QueueHandle(q);
  log::debug("opened OpenCL device ", device_.describe(), " with device profile '",
             device_profile_.name, "'");
  const char* prof = std::getenv("SGNLF_PROFILE");
  profiling_ = prof != nullptr && std::string(prof) != "0" && std::string(prof) != "";
}

Runtime::~Runtime() {
  if (!profile_.empty()) std::cerr << profile_report();
}

void Runtime::record(const std::string& kernel, double ms) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto& row = profile_[kernel];
  ++row.launches;
  row.total_ms += ms;
}

std::string Runtime::profile_report() const {
  std::vector<std::pair<std::string, ProfileRow>> rows(profile_.begin(), profile_.end());
  std::sort(rows.begin(), rows.end(),
            [](const auto& a, const auto& b) { return a.second.total_ms > b.second.total_ms; });
  double total = 0.0;
  for (const auto& r : rows) total += r.second.total_ms;
  std::ostringstream os;
  os << "kernel profile on " << device_.describe() << " (SGNLF_PROFILE; device time, "
     << std::fixed << std::setprecision(1) << total << " ms in all)\n";
  os << "  " << std::left << std::setw(40) << "kernel" << std::right << std::setw(10)
     << "launches" << std::setw(12) << "total ms" << std::setw(10) << "ms/launch" << std::setw(8)
     << "share" << "\n";
  for (const auto& [name, r] : rows)
    os << "  " << std::left << std::setw(40) << name << std::right << std::setw(10) << r.launches
       << std::setw(12) << std::setprecision(1) << r.total_ms << std::setw(10)
       << std::setprecision(3) << r.total_ms / double(r.launches) << std::setw(7)
       << std::setprecision(1) << 100.0 * r.total_ms / std::max(total, 1e-12) << "%\n";
  return os.str();
}

cl_program Runtime::program(const std::string& file, const std::string& options) {
  // The label names where the source came from, so that a build error points at the file a
  // user edited (SGNLF_KERNEL_DIR) or says the binary's embedded copy failed.
  const char* dir = std::getenv("SGNLF_KERNEL_DIR");
  const std::string label = dir && *dir ? std::string(dir) + "/" + file + " (SGNLF_KERNEL_DIR)"
                                        : file + " (embedded kernels/" + file + ")";
  return program_from_source(kernel_source(file), options, label);
}

cl_program Runtime::program_from_source(const std::string& source, const std::string& options,
                                        const std::string& label) {
  const std::string key = device_.name + "|" + device_.driver_version + "|" +
                          hex64(fnv1a64(source)) + "|" + options;
  std::lock_guard<std::mutex> lock(mutex_);
  if (auto it = programs_.find(key); it != programs_.end()) return it->second.get();

  const char* text = source.c_str();
  const size_t len = source.size();
  cl_int rc = CL_SUCCESS;
  cl_program p = clCreateProgramWithSource(context_.get(), 1, &text, &len, &rc);
  check(rc, "clCreateProgramWithSource", label);
  ProgramHandle handle(p);
  cl_device_id dev = device_.id;
  const std::string opts = "-cl-std=CL1.2 " + options;
  rc = clBuildProgram(p, 1, &dev, opts.c_str(), nullptr, nullptr);
  if (rc != CL_SUCCESS) {
    size_t n = 0;
    clGetProgramBuildInfo(p, dev, CL_PROGRAM_BUILD_LOG, 0, nullptr, &n);
    std::string build_log(n, '\0');
    if (n) clGetProgramBuildInfo(p, dev, CL_PROGRAM_BUILD_LOG, n, build_log.data(), nullptr);
    while (!build_log.empty() && build_log.back() == '\0') build_log.pop_back();
    throw BuildError("clBuildProgram failed: " + std::string(error_name(rc)) + " building '" +
                         label + "' for device '" + device_.name + "' (driver " +
                         device_.driver_version + ") with options '" + opts +
                         "'; build log:\n" + build_log,
                     build_log);
  }
  ++builds_;
  cl_program raw = handle.get();
  programs_.emplace(key, std::move(handle));
  return raw;
}

Kernel Runtime::kernel(const std::string& file, const std::string& name,
                       const std::string& options) {
  return Kernel(*this, program(file, options), name);
}

void Runtime::flush() { check(clFlush(queue_.get()), "clFlush"); }
void Runtime::finish() {
  if (trace_) ++trace_->finishes;
  check(clFinish(queue_.get()), "clFinish");
}

}  // namespace sgnlf::cl
