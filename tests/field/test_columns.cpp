// Device-vs-reference tests of kernels/field/columns.cl (a column of the density MLP's output
// <-> a plain vector) and kernels/field/accumulate.cl (dst += src). Bit equality: copies and one
// IEEE addition are exact by construction on any device.
#include <catch2/catch.hpp>

#include "core/rng.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

TEST_CASE("field_column_get/set match the host reference", "[field][columns]") {
  auto& rt = test::runtime();
  const int n = 1000, stride = 16, col = 3;
  std::vector<float> mat(size_t(n) * stride), vec(n);
  Rng rng(5);
  for (auto& v : mat) v = rng.uniform(-2, 2);
  for (auto& v : vec) v = rng.uniform(-2, 2);
  auto bm = cl::Buffer::from(rt, mat), bv = cl::Buffer::from(rt, vec);
  cl::Buffer out(rt, size_t(n) * 4);
  auto get = rt.kernel("field/columns.cl", "field_column_get");
  get.set_args(n, stride, col, bm, out).launch({cl::round_up(n, 64)}, {64}).wait();
  const auto g = out.read_vec<float>(n);
  std::vector<float> ref(n);
  for (int i = 0; i < n; ++i) ref[i] = mat[size_t(i) * stride + col];
  CHECK(g == ref);

  auto set = rt.kernel("field/columns.cl", "field_column_set");
  set.set_args(n, stride, col, bv, bm).launch({cl::round_up(n, 64)}, {64}).wait();
  const auto s = bm.read_vec<float>(mat.size());
  std::vector<float> ref_set = mat;
  for (int i = 0; i < n; ++i) ref_set[size_t(i) * stride + col] = vec[i];
  CHECK(s == ref_set);
}

TEST_CASE("field_accumulate matches the host reference", "[field][accumulate]") {
  auto& rt = test::runtime();
  const int n = 1000;
  std::vector<float> src(n + 5), dst(n + 5);
  Rng rng(8);
  for (auto& v : src) v = rng.uniform(-2, 2);
  for (auto& v : dst) v = rng.uniform(-2, 2);
  auto bs = cl::Buffer::from(rt, src), bd = cl::Buffer::from(rt, dst);
  rt.kernel("field/accumulate.cl", "field_accumulate")
      .set_args(n, bs, bd)
      .launch({cl::round_up(n, 64)}, {64})
      .wait();
  std::vector<float> ref = dst;  // the elements from n on stay untouched
  for (int i = 0; i < n; ++i) ref[size_t(i)] = dst[size_t(i)] + src[size_t(i)];
  CHECK(bd.read_vec<float>(ref.size()) == ref);
}
