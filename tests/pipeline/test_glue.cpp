// Device-vs-reference tests of kernels/pipeline/glue.cl (column gather/scatter, clamp).
#include <catch2/catch.hpp>

#include "core/rng.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

TEST_CASE("pipeline_column_get/set match the host reference", "[pipeline][glue][device]") {
  auto& rt = test::runtime();
  const int n = 1000, stride = 16, col = 3;
  std::vector<float> mat(size_t(n) * stride), vec(n);
  Rng rng(5);
  for (auto& v : mat) v = rng.uniform(-2, 2);
  for (auto& v : vec) v = rng.uniform(-2, 2);
  auto bm = cl::Buffer::from(rt, mat), bv = cl::Buffer::from(rt, vec);
  cl::Buffer out(rt, size_t(n) * 4);
  auto get = rt.kernel("pipeline/glue.cl", "pipeline_column_get");
  get.set_args(n, stride, col, bm, out).launch({cl::round_up(n, 64)}, {64}).wait();
  const auto g = out.read_vec<float>(n);
  std::vector<float> ref(n);
  for (int i = 0; i < n; ++i) ref[i] = mat[size_t(i) * stride + col];
  CHECK(g == ref);

  auto set = rt.kernel("pipeline/glue.cl", "pipeline_column_set");
  set.set_args(n, stride, col, bv, bm).launch({cl::round_up(n, 64)}, {64}).wait();
  const auto s = bm.read_vec<float>(mat.size());
  std::vector<float> ref_set = mat;
  for (int i = 0; i < n; ++i) ref_set[size_t(i) * stride + col] = vec[i];
  CHECK(s == ref_set);
}

TEST_CASE("pipeline_clamp_fwd matches the host reference", "[pipeline][glue][device]") {
  auto& rt = test::runtime();
  const int n = 3 * 777;
  std::vector<float> x(n);
  Rng rng(6);
  for (auto& v : x) v = rng.uniform(-3, 3);
  auto bx = cl::Buffer::from(rt, x);
  auto k = rt.kernel("pipeline/glue.cl", "pipeline_clamp_fwd");
  k.set_args(n, 1.0f, bx).launch({cl::round_up(n, 64)}, {64}).wait();
  const auto y = bx.read_vec<float>(n);
  int clamped = 0;
  for (int i = 0; i < n; ++i) {
    CHECK(y[i] == std::min(1.0f, std::max(-1.0f, x[i])));
    clamped += std::fabs(x[i]) > 1.0f;
  }
  CHECK(clamped > 0);
}
