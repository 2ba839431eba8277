// The field benchmarks' roofline probes (kernels/field/probe.cl) against host references: the
// runtime never calls them, but the benchmarks divide every kernel's rate by theirs.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>

#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

TEST_CASE("field_probe_gather sums the hashed entries of the table", "[field][probe]") {
  auto& rt = test::runtime();
  // 2^22 entries (32 MiB): the mask keeps every bit the hash sets, k << 20 included.
  const uint32_t entries = 1u << 22, mask = entries - 1;
  const int items = 300, per_item = 16;
  std::vector<float> table(size_t(entries) * 2);
  for (uint32_t e = 0; e < entries; ++e) {
    table[2 * e] = float(e % 4093) * 0.25f;
    table[2 * e + 1] = -float(e % 37);
  }
  auto b_t = cl::Buffer::from(rt, table);
  cl::Buffer b_out(rt, size_t(items) * 4);
  auto k = rt.kernel("field/probe.cl", "field_probe_gather");
  k.set_args(per_item, mask, b_t, b_out);
  k.launch({size_t(items)});
  const auto out = b_out.read_vec<float>(items);
  int mismatches = 0;
  for (int i = 0; i < items; ++i) {
    float ax = 0.0f, ay = 0.0f;
    for (int j = 0; j < per_item; ++j) {
      const uint32_t h = (uint32_t(i) * 2654435761u) ^ (uint32_t(j) * 805459861u) ^ (uint32_t(j) << 20);
      ax += table[2 * (h & mask)];
      ay += table[2 * (h & mask) + 1];
    }
    if (out[size_t(i)] != ax + ay) ++mismatches;
  }
  CHECK(mismatches == 0);
}

TEST_CASE("field_probe_copy copies and field_probe_fma follows its chains", "[field][probe]") {
  auto& rt = test::runtime();
  const int n4 = 257;
  std::vector<float> src(size_t(n4) * 4);
  for (size_t i = 0; i < src.size(); ++i) src[i] = float(i) * 0.5f - 3.0f;
  auto b_src = cl::Buffer::from(rt, src);
  cl::Buffer b_dst(rt, src.size() * 4);
  auto copy = rt.kernel("field/probe.cl", "field_probe_copy");
  copy.set_args(n4, b_src, b_dst);
  copy.launch({size_t(n4)});
  CHECK(b_dst.read_vec<float>(src.size()) == src);

  const int items = 64, iters = 50;
  const float a = 0.999f, b = 1e-6f;
  cl::Buffer b_out(rt, size_t(items) * 4);
  auto fma = rt.kernel("field/probe.cl", "field_probe_fma");
  fma.set_args(iters, a, b_out);
  fma.launch({size_t(items)});
  const auto out = b_out.read_vec<float>(items);
  double worst = 0;
  for (int i = 0; i < items; ++i) {
    const float offset[8] = {0.0f, 1e-3f, 2e-3f, 3e-3f, 4e-3f, 5e-3f, 6e-3f, 7e-3f};
    float x[8];
    x[0] = float(i) * 1e-7f;
    for (int c = 1; c < 8; ++c) x[c] = x[0] + offset[c];
    for (int it = 0; it < iters; ++it)
      for (float& v : x) v = std::fma(v, a, b);
    const float s = ((x[0] + x[1]) + (x[2] + x[3])) + ((x[4] + x[5]) + (x[6] + x[7]));
    const float ref = ((s + s) + s) + s;
    worst = std::max(worst, double(std::fabs(out[size_t(i)] - ref)) / std::max(1e-6, double(std::fabs(ref))));
  }
  CHECK(worst < 1e-6);
}
