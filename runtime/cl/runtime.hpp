// The OpenCL runtime of one device: context, in-order profiling queue and program cache.
//
// Program cache: key = (device name + driver version, FNV-1a hash of the fully inlined source,
// build options). Programs live as long as the Runtime; lookups are serialised by a mutex, so
// one Runtime may be shared by threads, but its queue is in-order and not meant to be fed from
// several threads at once. Specialisation goes through -D defines in the options string.
//
// Device profile (cl/device_profile.hpp): chosen when the Runtime opens (`profile_spec`, "" =
// SGNLF_DEVICE_PROFILE or automatic by device type); launchers read it when they are made.
#pragma once
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "cl/device.hpp"
#include "cl/device_profile.hpp"
#include "cl/launch_trace.hpp"
#include "cl/memory.hpp"

namespace sgnlf::cl {

class Runtime {
 public:
  // Opens the device chosen by `spec` (see select_device()) with the profile chosen by
  // `profile_spec` (see resolve_profile()).
  explicit Runtime(const std::string& spec = "", const std::string& profile_spec = "");
  explicit Runtime(const DeviceInfo& device, const std::string& profile_spec = "");
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;

  const DeviceInfo& device() const { return device_; }
  cl_context context() const { return context_.get(); }
  cl_command_queue queue() const { return queue_.get(); }
  const DeviceProfile& device_profile() const { return device_profile_; }
  // Replaces the profile (tests and benchmarks comparing variants); launchers made before keep
  // what they read from the old one.
  void set_device_profile(const DeviceProfile& p);

  // Builds (or returns the cached) program for a kernel file under kernels/.
  cl_program program(const std::string& file, const std::string& options = "");
  // Builds a program from source text (tests, probes). Cached like files.
  cl_program program_from_source(const std::string& source, const std::string& options = "",
                                 const std::string& label = "<inline>");
  // A new kernel object from a (cached) program.
  Kernel kernel(const std::string& file, const std::string& name,
                const std::string& options = "");

  void flush();
  void finish();
  size_t programs_built() const { return builds_; }

  // Kernel profile: when on (the constructor turns it on if SGNLF_PROFILE is set to anything
  // but "0"), every launch waits for its kernel and adds the device time to the kernel's row;
  // the destructor of a Runtime with a non-empty profile prints it to stderr. Serialises the
  // queue, so it is for finding where time goes, not for throughput numbers.
  struct ProfileRow {
    long launches = 0;
    double total_ms = 0.0;
  };
  void set_profiling(bool on) { profiling_ = on; }
  bool profiling() const { return profiling_; }
  void record(const std::string& kernel, double ms);
  const std::map<std::string, ProfileRow>& profile() const { return profile_; }
  std::string profile_report() const;
  // Launch trace (cl/launch_trace.hpp): while set, every launch, blocking transfer and finish
  // on this Runtime is appended to `t` (not owned; nullptr stops). Not thread-safe.
  void set_trace(LaunchTrace* t) { trace_ = t; }
  LaunchTrace* trace() const { return trace_; }
  ~Runtime();

 private:
  void open();
  DeviceInfo device_;
  DeviceProfile device_profile_;
  ContextHandle context_;
  QueueHandle queue_;
  std::mutex mutex_;
  std::map<std::string, ProgramHandle> programs_;
  size_t builds_ = 0;
  bool profiling_ = false;
  std::map<std::string, ProfileRow> profile_;
  LaunchTrace* trace_ = nullptr;
};

}  // namespace sgnlf::cl
