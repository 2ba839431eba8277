#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "cl/kernel_sources.hpp"
#include "cl/runtime.hpp"
#include "core/rng.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

TEST_CASE("a kernel with a syntax error throws with the build log", "[cl][build]") {
  auto& rt = test::runtime();
  const std::string bad = "__kernel void broken(__global float* x) { x[0] = 1.0f +; }\n";
  try {
    rt.program_from_source(bad, "", "broken.cl");
    FAIL("expected BuildError");
  } catch (const cl::BuildError& e) {
    const std::string msg = e.what();
    CHECK(!e.log().empty());
    CHECK_THAT(msg, Catch::Contains(e.log()));
    CHECK_THAT(msg, Catch::Contains(rt.device().name));
    CHECK_THAT(msg, Catch::Contains("broken.cl"));
    CHECK_THAT(e.log(), Catch::Contains("error"));
  }
}

TEST_CASE("unknown kernel names carry the call and error name", "[cl][build]") {
  auto& rt = test::runtime();
  try {
    rt.kernel("common/smoke.cl", "no_such_kernel");
    FAIL("expected ClError");
  } catch (const cl::ClError& e) {
    CHECK_THAT(e.what(), Catch::Contains("clCreateKernel") &&
                             Catch::Contains("CL_INVALID_KERNEL_NAME") &&
                             Catch::Contains("no_such_kernel"));
  }
}

TEST_CASE("saxpy on the device equals the host reference", "[cl][kernel]") {
  auto& rt = test::runtime();
  const int n = 10007;  // not a multiple of any work-group size
  std::vector<float> x(n), y(n), ref(n);
  Rng rng(11);
  for (int i = 0; i < n; ++i) {
    x[i] = rng.uniform(-2, 2);
    y[i] = rng.uniform(-2, 2);
    ref[i] = -0.75f * x[i] + y[i];
  }
  auto bx = cl::Buffer::from(rt, x), by = cl::Buffer::from(rt, y);
  auto k = rt.kernel("common/smoke.cl", "common_saxpy_fwd");
  k.set_args(n, -0.75f, bx, by);
  k.launch({size_t(n)});
  CHECK(test::max_abs_err(by.read_vec<float>(n), ref) <= 1e-6);
}

TEST_CASE("the program cache builds once per (source, options)", "[cl][cache]") {
  auto& rt = test::runtime();
  auto p1 = rt.program("common/smoke.cl");
  const size_t built = rt.programs_built();
  CHECK(rt.program("common/smoke.cl") == p1);
  CHECK(rt.programs_built() == built);
  auto p2 = rt.program("common/smoke.cl", "-DSGNLF_TEST_VARIANT=1");
  CHECK(p2 != p1);
  CHECK(rt.programs_built() == built + 1);
}

TEST_CASE("embedded kernels equal the files on disk", "[cl][embed]") {
  const auto& files = cl::embedded_files();
  REQUIRE(!files.empty());
  for (const auto& [name, text] : files) {
    std::ifstream f(std::string(SGNLF_KERNEL_ROOT) + "/" + std::string(name), std::ios::binary);
    REQUIRE(f);
    std::ostringstream s;
    s << f.rdbuf();
    INFO(name);
    CHECK(s.str() == std::string(text));
  }
}

TEST_CASE("includes are inlined and buffers reject out-of-range transfers", "[cl][embed]") {
  const auto src = cl::kernel_source("common/smoke.cl");
  CHECK_THAT(src, Catch::Contains("philox4x32_10"));
  CHECK_THAT(src, !Catch::Contains("#include"));
  auto& rt = test::runtime();
  cl::Buffer b(rt, 16);
  std::vector<float> v(8);
  CHECK_THROWS_AS(b.write(v.data(), 32), Error);
  CHECK_THROWS_AS(cl::kernel_source("no/such/file.cl"), Error);
}

TEST_CASE("the kernel profile counts launches and device time per kernel", "[cl][profile]") {
  auto& rt = test::runtime();
  const bool was = rt.profiling();
  const int n = 4096;
  std::vector<float> x(n, 1.0f), y(n, 2.0f);
  auto bx = cl::Buffer::from(rt, x), by = cl::Buffer::from(rt, y);
  auto k = rt.kernel("common/smoke.cl", "common_saxpy_fwd");
  k.set_args(n, 0.5f, bx, by);
  const long before = rt.profile().count("common_saxpy_fwd")
                          ? rt.profile().at("common_saxpy_fwd").launches
                          : 0;
  rt.set_profiling(true);
  for (int i = 0; i < 3; ++i) k.launch({size_t(n)});
  rt.set_profiling(false);
  k.launch({size_t(n)});  // not profiled
  rt.finish();
  rt.set_profiling(was);
  const auto& row = rt.profile().at("common_saxpy_fwd");
  CHECK(row.launches == before + 3);
  CHECK(row.total_ms > 0.0);  // three launches took measurable device time (>= 0 could not fail)
  const std::string report = rt.profile_report();
  CHECK_THAT(report, Catch::Contains("common_saxpy_fwd") && Catch::Contains(rt.device().name));
  // The launches really ran: y = 2 + 4 * 0.5
  CHECK(by.read_vec<float>(n)[0] == Approx(4.0f));
}
