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

TEST_CASE("pipeline_fine_points and pipeline_merge_encodings match the host reference",
          "[pipeline][glue][device]") {
  auto& rt = test::runtime();
  const int R = 37, S = 11, I = 5, M = S + I, width = 6;
  Rng rng(7);
  // Each ray's merged order is a random permutation of its S + I sources.
  std::vector<int> src(size_t(R) * M);
  for (int r = 0; r < R; ++r) {
    int* p = &src[size_t(r) * M];
    for (int k = 0; k < M; ++k) p[k] = k;
    for (int k = M - 1; k > 0; --k) std::swap(p[k], p[int(rng.next_u64() % uint64_t(k + 1))]);
  }
  auto rnd = [&](size_t n) {
    std::vector<float> v(n);
    for (auto& e : v) e = rng.uniform(-1, 1);
    return v;
  };
  const auto x = rnd(size_t(R) * M * 3), x_c = rnd(size_t(R) * S * 3);
  const auto enc_c = rnd(size_t(R) * S * width), enc_f = rnd(size_t(R) * I * width);
  auto bsrc = cl::Buffer::from(rt, src), bx = cl::Buffer::from(rt, x);
  auto bxc = cl::Buffer::from(rt, x_c), bec = cl::Buffer::from(rt, enc_c);
  auto bef = cl::Buffer::from(rt, enc_f);
  cl::Buffer bxf(rt, size_t(R) * I * 12), benc(rt, size_t(R) * M * width * 4);
  const size_t global = cl::round_up(size_t(R) * M, 64);
  auto pick = rt.kernel("pipeline/glue.cl", "pipeline_fine_points");
  pick.set_args(R, S, M, bsrc, bx, bxf).launch({global}, {64}).wait();
  auto merge = rt.kernel("pipeline/glue.cl", "pipeline_merge_encodings");
  merge.set_args(R, S, M, width, bsrc, bxc, bec, bef, bx, benc).launch({global}, {64}).wait();

  std::vector<float> xf_ref(size_t(R) * I * 3), x_ref = x, enc_ref(size_t(R) * M * width);
  for (int r = 0; r < R; ++r)
    for (int k = 0; k < M; ++k) {
      const size_t q = size_t(r) * M + k;
      const int s = src[q];
      for (int c = 0; c < 3; ++c) {
        if (s >= S) xf_ref[(size_t(r) * I + (s - S)) * 3 + c] = x[3 * q + c];
        else x_ref[3 * q + c] = x_c[(size_t(r) * S + s) * 3 + c];
      }
      for (int c = 0; c < width; ++c)
        enc_ref[q * width + c] = s < S ? enc_c[(size_t(r) * S + s) * width + c]
                                       : enc_f[(size_t(r) * I + (s - S)) * width + c];
    }
  CHECK(bxf.read_vec<float>(xf_ref.size()) == xf_ref);
  CHECK(bx.read_vec<float>(x_ref.size()) == x_ref);
  CHECK(benc.read_vec<float>(enc_ref.size()) == enc_ref);
}

TEST_CASE("early ray termination kernels match the host reference", "[pipeline][glue][device]") {
  auto& rt = test::runtime();
  const int R = 53, S = 12, I = 6, M = S + I;
  const float eps = 1e-3f;
  Rng rng(17);
  // Coarse weights: some rays opaque early (T falls below eps at a random sample), some never.
  std::vector<float> t_c(size_t(R) * S), w_c(size_t(R) * S), t(size_t(R) * M);
  for (int r = 0; r < R; ++r) {
    const int hit = int(rng.next_u64() % uint64_t(S + 4));  // ≥ S: no surface
    float trans = 1.0f;
    for (int j = 0; j < S; ++j) {
      t_c[size_t(r) * S + j] = 0.1f + 0.2f * j + 0.05f * rng.uniform(0, 1);
      const float alpha = j == hit ? 0.99999f : (j > hit ? 0.5f : 0.01f);
      w_c[size_t(r) * S + j] = trans * alpha;
      trans *= 1.0f - alpha;
    }
    std::vector<float> tm(t_c.begin() + r * S, t_c.begin() + (r + 1) * S);
    for (int k = 0; k < I; ++k) tm.push_back(rng.uniform(0.1f, 2.6f));
    std::sort(tm.begin(), tm.end());
    std::copy(tm.begin(), tm.end(), t.begin() + r * M);
  }
  auto btc = cl::Buffer::from(rt, t_c), bwc = cl::Buffer::from(rt, w_c), bt = cl::Buffer::from(rt, t);
  cl::Buffer bcount(rt, size_t(R) * 4);
  auto live = rt.kernel("pipeline/glue.cl", "pipeline_live_count");
  live.set_args(R, S, M, eps, btc, bwc, bt, bcount).launch({cl::round_up(size_t(R), 64)}, {64}).wait();
  const auto count = bcount.read_vec<int32_t>(size_t(R));
  std::vector<int32_t> offset{0};
  int terminated = 0;
  for (int r = 0; r < R; ++r) {
    // Reference: the first coarse sample after which 1 − Σ w < eps, plus one more coarse bin.
    float acc = 0.0f;
    int expect = M;
    for (int j = 0; j + 2 < S; ++j) {
      acc += w_c[size_t(r) * S + j];
      if (1.0f - acc < eps) {
        const float t_stop = t_c[size_t(r) * S + j + 2];
        expect = 0;
        while (expect < M && t[size_t(r) * M + expect] <= t_stop) ++expect;
        break;
      }
    }
    terminated += expect < M;
    CHECK(count[size_t(r)] == expect);
    offset.push_back(offset.back() + expect);
  }
  CHECK(terminated > 10);
  CHECK(terminated < R);
  const int n = offset.back();
  auto boff = cl::Buffer::from(rt, offset);
  // Row → ray map.
  cl::Buffer bray(rt, size_t(n) * 4);
  rt.kernel("pipeline/glue.cl", "pipeline_row_ray")
      .set_args(R, boff, bray)
      .launch({cl::round_up(size_t(R), 64)}, {64})
      .wait();
  std::vector<int32_t> ray_ref;
  for (int r = 0; r < R; ++r)
    for (int k = 0; k < count[size_t(r)]; ++k) ray_ref.push_back(r);
  CHECK(bray.read_vec<int32_t>(size_t(n)) == ray_ref);
  // Compaction of rows (width 3) and the expansion of the field outputs back.
  const int width = 3;
  std::vector<float> full(size_t(R) * M * width);
  for (auto& v : full) v = rng.uniform(-1, 1);
  auto bfull = cl::Buffer::from(rt, full);
  cl::Buffer bcomp(rt, size_t(n) * width * 4);
  const size_t global = cl::round_up(size_t(R) * M, 64);
  rt.kernel("pipeline/glue.cl", "pipeline_compact_rows")
      .set_args(R, M, width, boff, bfull, bcomp)
      .launch({global}, {64})
      .wait();
  std::vector<float> comp_ref;
  for (int r = 0; r < R; ++r)
    for (int k = 0; k < count[size_t(r)]; ++k)
      for (int c = 0; c < width; ++c) comp_ref.push_back(full[(size_t(r) * M + k) * width + c]);
  CHECK(bcomp.read_vec<float>(comp_ref.size()) == comp_ref);
  const int stride = 16;
  std::vector<float> dens(size_t(n) * stride), head_c(size_t(n) * 2);
  for (auto& v : dens) v = rng.uniform(-3, 3);
  for (auto& v : head_c) v = rng.uniform(-3, 3);
  auto bdens = cl::Buffer::from(rt, dens), bhc = cl::Buffer::from(rt, head_c);
  auto bh0 = cl::Buffer::from(rt, std::vector<float>(size_t(R) * M, 9.0f));
  auto bhead = cl::Buffer::from(rt, std::vector<float>(size_t(R) * M * 2, 9.0f));
  rt.kernel("pipeline/glue.cl", "pipeline_expand_outputs")
      .set_args(R, M, stride, -100.0f, boff, bdens, bhc, bh0, bhead)
      .launch({global}, {64})
      .wait();
  std::vector<float> h0_ref(size_t(R) * M, -100.0f), head_ref(size_t(R) * M * 2, 0.0f);
  for (int r = 0; r < R; ++r)
    for (int k = 0; k < count[size_t(r)]; ++k) {
      const size_t q = size_t(r) * M + k, row = size_t(offset[size_t(r)] + k);
      h0_ref[q] = dens[row * stride];
      head_ref[2 * q] = head_c[2 * row];
      head_ref[2 * q + 1] = head_c[2 * row + 1];
    }
  CHECK(bh0.read_vec<float>(h0_ref.size()) == h0_ref);
  CHECK(bhead.read_vec<float>(head_ref.size()) == head_ref);
}
