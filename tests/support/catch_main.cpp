// Catch2 v2 main shared by every test binary. A binary that contains device tests exits with
// 77 (CTest SKIP_RETURN_CODE) when no OpenCL platform exists at all, and only then. The shared
// test Runtime is released before main returns.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdio>

#include "cl/shared_runtime.hpp"
#include "support/test_device.hpp"

int main(int argc, char** argv) {
  Catch::Session session;
  if (const int rc = session.applyCommandLine(argc, argv); rc != 0) return rc;
  if (sgnlf::test::binary_needs_device() && !sgnlf::cl::any_device_available()) {
    std::fprintf(stderr, "no OpenCL platform found: device tests skipped (install pocl-opencl-icd)\n");
    return 77;
  }
  const int rc = session.run();
  // Before main returns, not at exit: runtime/cl/shared_runtime.hpp says why.
  sgnlf::cl::release_shared_runtime();
  return rc;
}
