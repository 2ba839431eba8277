#include <catch2/catch.hpp>

#include "cl/runtime.hpp"
#include "core/rng.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

TEST_CASE("Philox on the device equals the host stream word for word", "[cl][rng]") {
  auto& rt = test::runtime();
  const int n_blocks = 4096;
  const uint64_t seed = 0x123456789abcdef0ull;
  const uint32_t stream = 7;
  cl::Buffer out(rt, size_t(n_blocks) * 16);
  auto k = rt.kernel("common/smoke.cl", "common_philox_fill");
  k.set_args(uint32_t(seed), uint32_t(seed >> 32), stream, n_blocks, out);
  k.launch({size_t(n_blocks)});
  const auto dev = out.read_vec<uint32_t>(size_t(n_blocks) * 4);
  Rng host(seed, stream);
  size_t mismatches = 0;
  double mean = 0;
  for (size_t i = 0; i < dev.size(); ++i) {
    mismatches += dev[i] != host.next_u32();
    mean += u32_to_unit_float(dev[i]);
  }
  CHECK(mismatches == 0);
  CHECK(mean / dev.size() == Approx(0.5).margin(0.01));
}
