// A kernel that fails to build names the device, the kernel file (with the folder it was read
// from when SGNLF_KERNEL_DIR is set) and the build log.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "cl/kernel_sources.hpp"
#include "cl/runtime.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

TEST_CASE("a kernel file that fails to build names the device, the file and the build log",
          "[cl][build]") {
  auto& rt = test::runtime();
  const std::string dir = test::temp_dir("broken_kernels");
  std::filesystem::create_directories(dir + "/common");
  std::string src = cl::kernel_source("common/smoke.cl");
  src += "\n__kernel void common_broken_fwd(__global float* x) { x[0] = undeclared_name; }\n";
  std::ofstream(dir + "/common/smoke.cl") << src;
  ::setenv("SGNLF_KERNEL_DIR", dir.c_str(), 1);
  std::string msg, log;
  try {
    rt.program("common/smoke.cl");
  } catch (const cl::BuildError& e) {
    msg = e.what();
    log = e.log();
  }
  ::unsetenv("SGNLF_KERNEL_DIR");
  INFO(msg);
  REQUIRE_FALSE(msg.empty());
  CHECK_THAT(msg, Catch::Contains(dir + "/common/smoke.cl") && Catch::Contains("SGNLF_KERNEL_DIR"));
  CHECK_THAT(msg, Catch::Contains(rt.device().name) && Catch::Contains(rt.device().driver_version));
  CHECK_THAT(log, Catch::Contains("undeclared_name"));
  CHECK_THAT(msg, Catch::Contains(log));
  // Without SGNLF_KERNEL_DIR the embedded copy is used again, and builds.
  CHECK_NOTHROW(rt.program("common/smoke.cl"));
}
