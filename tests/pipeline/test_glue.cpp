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

TEST_CASE("coarse wave kernels match the host reference", "[pipeline][glue][device]") {
  auto& rt = test::runtime();
  const int R = 41, S = 16, lf = 5, stride = 16;
  const float eps = 1e-3f;
  Rng rng(23);
  // Coarse weights of rays that become opaque at a random sample (≥ S: never).
  std::vector<float> w_c(size_t(R) * S);
  for (int r = 0; r < R; ++r) {
    const int hit = int(rng.next_u64() % uint64_t(S + 3));
    float trans = 1.0f;
    for (int j = 0; j < S; ++j) {
      const float alpha = j == hit ? 0.99999f : (j > hit ? 0.5f : 0.02f);
      w_c[size_t(r) * S + j] = trans * alpha;
      trans *= 1.0f - alpha;
    }
  }
  auto bwc = cl::Buffer::from(rt, w_c);
  cl::Buffer bdone(rt, size_t(R) * 4);
  auto done_k = rt.kernel("pipeline/glue.cl", "pipeline_wave_done");
  int n_done_mid = 0, n_done_end = 0;
  for (int end : {4, 8, 12, 16}) {
    done_k.set_args(R, S, end, eps, bwc, bdone).launch({cl::round_up(size_t(R), 64)}, {64}).wait();
    const auto done = bdone.read_vec<int32_t>(size_t(R));
    for (int r = 0; r < R; ++r) {
      // Reference: the termination index j + 2 of pipeline_live_count lies below `end`.
      float acc = 0.0f;
      int stop = -1;
      for (int j = 0; j + 2 < S; ++j) {
        acc += w_c[size_t(r) * S + j];
        if (1.0f - acc < eps) {
          stop = j + 2;
          break;
        }
      }
      const int expect = stop >= 0 && stop < end ? 1 : 0;
      CHECK(done[size_t(r)] == expect);
      if (end == 8) n_done_mid += expect;
      if (end == 16) n_done_end += expect;
    }
  }
  CHECK(n_done_mid > 3);        // some rays stop in the first half
  CHECK(n_done_end > n_done_mid);  // more by the end
  CHECK(n_done_end < R);        // and some never

  // Gather of one wave's rows of the alive rays, and the scatter of its outputs back.
  const int s0 = 5, width = 6;
  std::vector<int32_t> alive;
  for (int r = 0; r < R; ++r)
    if (rng.uniform(0, 1) < 0.6f) alive.push_back(r);
  const int n_alive = int(alive.size()), rows = n_alive * width;
  std::vector<float> x_c(size_t(R) * S * 3), enc_w(size_t(rows) * lf), dens_w(size_t(rows) * stride);
  for (auto& v : x_c) v = rng.uniform(-1, 1);
  for (auto& v : enc_w) v = rng.uniform(-1, 1);
  for (auto& v : dens_w) v = rng.uniform(-3, 3);
  auto balive = cl::Buffer::from(rt, alive), bxc = cl::Buffer::from(rt, x_c);
  cl::Buffer bxw(rt, size_t(rows) * 3 * 4);
  const size_t global = cl::round_up(size_t(rows), 64);
  rt.kernel("pipeline/glue.cl", "pipeline_wave_gather")
      .set_args(n_alive, S, s0, width, balive, bxc, bxw)
      .launch({global}, {64})
      .wait();
  std::vector<float> xw_ref;
  for (int a = 0; a < n_alive; ++a)
    for (int i = 0; i < width; ++i)
      for (int c = 0; c < 3; ++c) xw_ref.push_back(x_c[(size_t(alive[size_t(a)]) * S + s0 + i) * 3 + c]);
  CHECK(bxw.read_vec<float>(xw_ref.size()) == xw_ref);
  std::vector<float> enc_ref(size_t(R) * S * lf, 7.0f), h0_ref(size_t(R) * S, -100.0f);
  auto bencw = cl::Buffer::from(rt, enc_w), bdensw = cl::Buffer::from(rt, dens_w);
  auto benc = cl::Buffer::from(rt, enc_ref), bh0 = cl::Buffer::from(rt, h0_ref);
  rt.kernel("pipeline/glue.cl", "pipeline_wave_scatter")
      .set_args(n_alive, S, s0, width, lf, stride, balive, bencw, bdensw, benc, bh0)
      .launch({global}, {64})
      .wait();
  for (int a = 0; a < n_alive; ++a)
    for (int i = 0; i < width; ++i) {
      const size_t q = size_t(a) * width + i, dst = size_t(alive[size_t(a)]) * S + s0 + i;
      for (int k = 0; k < lf; ++k) enc_ref[dst * lf + k] = enc_w[q * lf + k];
      h0_ref[dst] = dens_w[q * stride];
    }
  CHECK(benc.read_vec<float>(enc_ref.size()) == enc_ref);
  CHECK(bh0.read_vec<float>(h0_ref.size()) == h0_ref);
  // pipeline_fill.
  cl::Buffer bf(rt, 70 * 4);
  rt.kernel("pipeline/glue.cl", "pipeline_fill").set_args(70, -3.5f, bf).launch({128}, {64}).wait();
  CHECK(bf.read_vec<float>(70) == std::vector<float>(70, -3.5f));
}

TEST_CASE("head band kernels match the host reference", "[pipeline][glue][device]") {
  auto& rt = test::runtime();
  const int R = 37, M = 20, stride = 16;
  const float thr = 1e-4f;
  Rng rng(29);
  // Live prefixes of random length, weights with a random band above thr (some rays none).
  std::vector<int32_t> live_off{0};
  std::vector<float> w(size_t(R) * M, 0.0f);
  for (int r = 0; r < R; ++r) {
    const int live = int(rng.next_u64() % uint64_t(M + 1));
    live_off.push_back(live_off.back() + live);
    for (int s = 0; s < M; ++s)
      w[size_t(r) * M + s] = rng.uniform(0, 1) < 0.3f ? rng.uniform(0.0f, 0.5f) : rng.uniform(0.0f, 0.9f * thr);
  }
  auto blo = cl::Buffer::from(rt, live_off), bw = cl::Buffer::from(rt, w);
  cl::Buffer bbegin(rt, size_t(R) * 4), bcount(rt, size_t(R) * 4);
  rt.kernel("pipeline/glue.cl", "pipeline_head_band")
      .set_args(R, M, thr, blo, bw, bbegin, bcount)
      .launch({cl::round_up(size_t(R), 64)}, {64})
      .wait();
  const auto begin = bbegin.read_vec<int32_t>(size_t(R)), count = bcount.read_vec<int32_t>(size_t(R));
  std::vector<int32_t> band_off{0};
  int empty = 0, partial = 0;
  for (int r = 0; r < R; ++r) {
    const int live = live_off[size_t(r) + 1] - live_off[size_t(r)];
    int first = -1, last = -1;
    for (int s = 0; s < live; ++s)
      if (w[size_t(r) * M + s] > thr) {
        if (first < 0) first = s;
        last = s;
      }
    const int eb = first < 0 ? 0 : first, ec = first < 0 ? 0 : last - first + 1;
    CHECK(begin[size_t(r)] == eb);
    CHECK(count[size_t(r)] == ec);
    empty += ec == 0;
    partial += ec > 0 && ec < live;
    band_off.push_back(band_off.back() + ec);
  }
  CHECK(empty > 0);
  CHECK(partial > 5);
  const int n_band = band_off.back(), n_live = live_off.back();
  auto bbo = cl::Buffer::from(rt, band_off);
  const size_t global = cl::round_up(size_t(R) * M, 64);
  // Gather from the live layout (width 16) and from the full layout (width 2).
  std::vector<float> live_rows(size_t(n_live) * stride), full_rows(size_t(R) * M * 2);
  for (auto& v : live_rows) v = rng.uniform(-1, 1);
  for (auto& v : full_rows) v = rng.uniform(-1, 1);
  auto blive = cl::Buffer::from(rt, live_rows), bfull = cl::Buffer::from(rt, full_rows);
  cl::Buffer bgl(rt, size_t(n_band) * stride * 4), bgf(rt, size_t(n_band) * 2 * 4);
  auto gather = rt.kernel("pipeline/glue.cl", "pipeline_band_gather");
  gather.set_args(R, M, stride, blo, bbegin, bbo, blive, bgl, 1).launch({global}, {64}).wait();
  gather.set_args(R, M, 2, blo, bbegin, bbo, bfull, bgf, 0).launch({global}, {64}).wait();
  std::vector<float> gl_ref, gf_ref;
  for (int r = 0; r < R; ++r)
    for (int i = 0; i < count[size_t(r)]; ++i) {
      const size_t lrow = size_t(live_off[size_t(r)] + begin[size_t(r)] + i);
      const size_t frow = size_t(r) * M + size_t(begin[size_t(r)] + i);
      for (int k = 0; k < stride; ++k) gl_ref.push_back(live_rows[lrow * stride + k]);
      for (int k = 0; k < 2; ++k) gf_ref.push_back(full_rows[frow * 2 + k]);
    }
  CHECK(bgl.read_vec<float>(gl_ref.size()) == gl_ref);
  CHECK(bgf.read_vec<float>(gf_ref.size()) == gf_ref);
  // Scatter of band rows into the live layout (zeros elsewhere) and the head expansion.
  auto bscat = cl::Buffer::from(rt, std::vector<float>(size_t(n_live) * stride, 5.0f));
  rt.kernel("pipeline/glue.cl", "pipeline_band_scatter_live")
      .set_args(R, M, stride, blo, bbegin, bbo, bgl, bscat)
      .launch({global}, {64})
      .wait();
  std::vector<float> scat_ref(size_t(n_live) * stride, 0.0f);
  for (int r = 0; r < R; ++r)
    for (int i = 0; i < count[size_t(r)]; ++i) {
      const size_t lrow = size_t(live_off[size_t(r)] + begin[size_t(r)] + i);
      for (int k = 0; k < stride; ++k) scat_ref[lrow * stride + k] = live_rows[lrow * stride + k];
    }
  CHECK(bscat.read_vec<float>(scat_ref.size()) == scat_ref);
  std::vector<float> head_b(size_t(n_band) * 2);
  for (auto& v : head_b) v = rng.uniform(-3, 3);
  auto bhb = cl::Buffer::from(rt, head_b);
  auto bhead = cl::Buffer::from(rt, std::vector<float>(size_t(R) * M * 2, 9.0f));
  rt.kernel("pipeline/glue.cl", "pipeline_band_expand_head")
      .set_args(R, M, -30.0f, bbegin, bbo, bhb, bhead)
      .launch({global}, {64})
      .wait();
  std::vector<float> head_ref(size_t(R) * M * 2, -30.0f);
  for (int r = 0; r < R; ++r)
    for (int i = 0; i < count[size_t(r)]; ++i) {
      const size_t q = size_t(r) * M + size_t(begin[size_t(r)] + i), row = size_t(band_off[size_t(r)] + i);
      head_ref[2 * q] = head_b[2 * row];
      head_ref[2 * q + 1] = head_b[2 * row + 1];
    }
  CHECK(bhead.read_vec<float>(head_ref.size()) == head_ref);
}
