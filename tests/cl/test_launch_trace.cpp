// The launch trace (cl/launch_trace.hpp): what it records of launches, blocking transfers and
// finishes, and that it records nothing once unset.
#include <catch2/catch.hpp>

#include "cl/launch_trace.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;

using namespace sgnlf;

TEST_CASE("the launch trace records work-items, the largest buffer and blocking transfers",
          "[trace]") {
  auto& rt = test::runtime();
  const int n = 1000;
  auto x = cl::Buffer::from(rt, std::vector<float>(n, 1.0f));
  cl::Buffer y(rt, size_t(4 * n) * sizeof(float));  // larger than n floats: the largest argument
  y.fill_zero();
  auto k = rt.kernel("common/smoke.cl", "common_saxpy_fwd");
  k.set_args(n, 2.0f, x, y);
  cl::LaunchTrace t;
  rt.set_trace(&t);
  y.write_vec(std::vector<float>(n, 0.5f));  // before any launch
  k.launch({1024});
  const auto out = y.read_vec<float>(n);
  rt.finish();
  rt.set_trace(nullptr);
  k.launch({1024});
  (void)y.read_vec<float>(1);
  CHECK(out[0] == Approx(2.5f));
  REQUIRE(t.launches.size() == 1);
  CHECK(t.launches[0].kernel == "common_saxpy_fwd");
  CHECK(t.launches[0].work_items == 1024);
  CHECK(t.launches[0].largest_buffer_bytes == size_t(4 * n) * sizeof(float));
  REQUIRE(t.blocking_transfers.size() == 2);
  CHECK_FALSE(t.blocking_transfers[0].read);
  CHECK(t.blocking_transfers[0].bytes == size_t(n) * sizeof(float));
  CHECK(t.blocking_transfers[0].after_kernel == "(trace start)");
  CHECK(t.blocking_transfers[1].read);
  CHECK(t.blocking_transfers[1].after_kernel == "common_saxpy_fwd");
  CHECK(t.finishes == 1);
  // Rebinding an argument replaces its size: with x in both buffer places, x is the largest.
  k.set_arg(3, x);
  t.clear();
  rt.set_trace(&t);
  k.launch({1024});
  rt.set_trace(nullptr);
  rt.finish();
  CHECK(t.launches.at(0).largest_buffer_bytes == size_t(n) * sizeof(float));
}
