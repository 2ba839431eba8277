// Roofline probe kernels against host references (the runtime never calls these), and the
// context block's fields.
#include <cmath>

#include "core/config.hpp"
#include "harness/context.hpp"
#include "harness/roofline.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;

using namespace sgnlf;

namespace {
// Host reference of roofline_fma_peak for one work-item (same chains, same summation order).
float fma_reference(int gid, int iters) {
  float lane[16];
  for (int l = 0; l < 16; ++l) lane[l] = float(l) * 0.0625f;
  const float base = float(gid & 1023) * (1.0f / 1024.0f);
  float x[8][16];
  for (int l = 0; l < 16; ++l) {
    x[0][l] = lane[l] + base;
    x[1][l] = lane[l] - base;
    x[2][l] = lane[l] * 0.5f + base;
    x[3][l] = lane[l] * 0.25f - base;
    x[4][l] = base - lane[l];
    x[5][l] = lane[l] + 2.0f * base;
    x[6][l] = lane[l] * 0.75f;
    x[7][l] = lane[l] + 0.5f;
  }
  for (int i = 0; i < iters; ++i)
    for (auto& c : x)
      for (float& v : c) v = std::fma(v, harness::kFmaA, harness::kFmaB);
  float s[16];
  for (int l = 0; l < 16; ++l)
    s[l] = ((x[0][l] + x[1][l]) + (x[2][l] + x[3][l])) + ((x[4][l] + x[5][l]) + (x[6][l] + x[7][l]));
  float h8[8], h4[4], h2[2];
  for (int l = 0; l < 8; ++l) h8[l] = s[l] + s[l + 8];
  for (int l = 0; l < 4; ++l) h4[l] = h8[l] + h8[l + 4];
  for (int l = 0; l < 2; ++l) h2[l] = h4[l] + h4[l + 2];
  return h2[0] + h2[1];
}
}  // namespace

TEST_CASE("roofline_fma_peak matches the host reference", "[harness][device]") {
  harness::RooflineProbe probe(test::runtime());
  for (int iters : {1, 7, 300}) {
    const size_t n = 2048;
    probe.run_fma(n, iters);
    const auto out = probe.fma_output(n);
    std::vector<float> ref(n);
    for (size_t i = 0; i < n; ++i) ref[i] = fma_reference(int(i), iters);
    INFO("iters " << iters);
    CHECK(test::max_sym_rel_err(out, ref) < 1e-6);
  }
  CHECK(harness::fma_flops(10, 3) == 2.0 * 8 * 16 * 3 * 10);
}

TEST_CASE("roofline copy and triad match the host reference", "[harness][device]") {
  harness::RooflineProbe probe(test::runtime());
  const size_t n = 1 << 16;
  probe.alloc_stream(n);
  probe.run_copy();
  // Bit equality: a copy, and a triad of small integers, exact in float on any device.
  CHECK(test::max_abs_err(probe.stream_output(), std::vector<float>(n, 1.0f)) == 0.0);
  probe.run_triad(3.0f);  // a = b + 3 c = 1 + 6
  CHECK(test::max_abs_err(probe.stream_output(), std::vector<float>(n, 7.0f)) == 0.0);
  CHECK(harness::triad_bytes(n) == 12.0 * n);
  CHECK_THROWS_AS(probe.alloc_stream(6), Error);
}

TEST_CASE("roofline gather sums the hashed entries of the table", "[harness][device]") {
  harness::RooflineProbe probe(test::runtime());
  // 2^22 entries (32 MiB): the mask keeps every bit the hash sets, k << 20 included.
  const uint32_t entries = 1u << 22, mask = entries - 1;
  std::vector<float> table(size_t(entries) * 2);
  for (uint32_t e = 0; e < entries; ++e) {
    table[2 * e] = float(e % 4093) * 0.25f;
    table[2 * e + 1] = -float(e % 37);
  }
  probe.alloc_gather(table);
  const size_t items = 300;
  probe.run_gather(items);
  const auto out = probe.gather_output(items);
  int mismatches = 0;
  for (uint32_t i = 0; i < items; ++i) {
    float ax = 0.0f, ay = 0.0f;
    for (uint32_t k = 0; k < uint32_t(harness::kGatherPerItem); ++k) {
      const uint32_t e = harness::gather_entry(i, k, mask);
      ax += table[2 * e];
      ay += table[2 * e + 1];
    }
    if (out[i] != ax + ay) ++mismatches;
  }
  CHECK(mismatches == 0);
  CHECK_THROWS_AS(probe.alloc_gather_zero(1000), Error);  // not a power of two
}

TEST_CASE("measure_roofline returns positive summaries", "[harness][device]") {
  harness::RooflineOptions o;
  o.target_launch_ms = 5;
  o.repetitions = 3;
  o.stream_floats = 1 << 20;
  o.gather_entries = 1 << 20;
  o.gather_items = 1 << 14;
  const Json r = harness::measure_roofline(test::runtime(), o);
  CHECK(r["gathers_per_s"]["n"] == 3);
  CHECK(r["gathers_per_s_best"].get<double>() >= r["gathers_per_s"]["median"].get<double>());
  CHECK(r["gathers_per_s_best"].get<double>() > 0);
  CHECK(r["peak_gflops"]["n"] == 3);
  CHECK(r["peak_gflops_best"].get<double>() > 0);
  CHECK(r["triad_gbs"]["median"].get<double>() > 0);
  CHECK(r["peak_gflops_best"].get<double>() >= r["peak_gflops"]["median"].get<double>());
}

TEST_CASE("context block: git, build, machine, OpenCL, device profile", "[harness]") {
  const auto dev = test::runtime().device();
  const Json c = harness::context_block(&dev);
  const std::string sha = c["git"]["sha"];
  CHECK(sha.size() == 40);
  CHECK(c["git"]["dirty"].is_boolean());
  CHECK(c["build"]["compiler"] != "");
  CHECK(c["build"]["libraries"]["eigen"] != "");
  const std::string built = c["build"]["git"]["sha"];  // stamped when this test was built
  CHECK(built.size() == 40);
  CHECK(c["build"]["git"]["dirty"].is_boolean());
  CHECK(c["machine"]["logical_cores"].get<int>() > 0);
  CHECK(c["machine"]["mem_total_kib"].get<long long>() > 0);
  CHECK(c["opencl"]["device"] == dev.name);
  CHECK(c["pocl_env"].is_object());
  // The device profile: the one a Runtime on the device opens by default, or the one given.
  CHECK(c["device_profile"] == cl::resolve_profile("", dev).to_json());
  const cl::DeviceProfile gpu = cl::gpu_profile();
  CHECK(harness::context_block(&dev, &gpu)["device_profile"]["encoder_backward"] ==
        "deterministic_parallel");
  CHECK(harness::context_block(nullptr)["device_profile"].is_null());
  CHECK(harness::peak_rss_kib() > 0);
  const auto flat = harness::flatten(Json{{"a", {{"b", 1}, {"c", "x"}}}});
  REQUIRE(flat.size() == 2);
  CHECK(flat[0] == std::make_pair(std::string("a.b"), std::string("1")));
  CHECK(flat[1] == std::make_pair(std::string("a.c"), std::string("x")));
}
