// The context block every result carries (results/schema.md, "context"): git sha and dirty
// flag, build, machine, OpenCL device strings, POCL_* environment and peak host memory. The
// table harness writes it into its JSON; the kernel benchmarks add it to Google Benchmark's
// context (benchmarks/support), so both kinds of numbers say where they came from.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "cl/device.hpp"
#include "cl/device_profile.hpp"
#include "core/config_fwd.hpp"

namespace sgnlf::harness {

// {sha, dirty, describe, source: "git" | "configure"}: read with `git` from the source tree at
// run time; falls back to the sha baked at configure time when git or the tree is absent.
Json git_info();
// Compiler, flags, build type, library versions (generated at configure time), and `git`:
// build_git() below.
Json build_info();
// {sha, dirty, changed_paths} of the source tree when this binary was built (null dirty and
// changed_paths when git was unavailable then; cmake/GitStamp.cmake).
Json build_git();
// CPU model, logical cores, MemTotal, OS (/etc/os-release), kernel release.
Json machine_info();
// Platform, device, driver and OpenCL C strings of one device.
Json opencl_info(const cl::DeviceInfo& device);
// Every POCL_* variable of the environment (empty object when none).
Json pocl_env();
// Peak resident set size of this process in KiB (getrusage).
long peak_rss_kib();
// The full block; `device` may be null (no OpenCL device in use). `profile`: the device profile
// the runs use (cl::Runtime::device_profile()); null = the one a Runtime on `device` opens
// without an explicit spec (SGNLF_DEVICE_PROFILE, else automatic).
Json context_block(const cl::DeviceInfo* device, const cl::DeviceProfile* profile = nullptr);
// Flattens a JSON object into ("a.b.c", "value") pairs (for Google Benchmark's context).
std::vector<std::pair<std::string, std::string>> flatten(const Json& j,
                                                         const std::string& prefix = "");

}  // namespace sgnlf::harness
