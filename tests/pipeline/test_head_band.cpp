// Device-vs-reference tests of kernels/pipeline/head_band.cl (pipeline::HeadBand): the band per
// ray, the band gather, its scatter into the live layout and the head expansion; and the
// launcher itself. Bit equality: comparisons with the threshold, index maps and copies, exact by
// construction.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/rng.hpp"
#include "pipeline/model/head_band.hpp"
#include "pipeline/model/sample_compaction.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

TEST_CASE("head band kernels match the host reference", "[pipeline][head-band][device]") {
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
  rt.kernel("pipeline/head_band.cl", "pipeline_head_band")
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
  auto gather = rt.kernel("pipeline/head_band.cl", "pipeline_band_gather");
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
  rt.kernel("pipeline/head_band.cl", "pipeline_band_scatter_live")
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
  rt.kernel("pipeline/head_band.cl", "pipeline_band_expand_head")
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

TEST_CASE("HeadBand cuts the band of the live rows, gathers and expands it",
          "[pipeline][head-band][device]") {
  auto& rt = test::runtime();
  const int R = 43, S = 16, M = S, stride = 16;  // uniform-only sampling: merged = coarse
  const float eps = 1e-3f, thr = 1e-4f;
  Rng rng(53);
  // Live prefixes from a SampleCompaction over rays that become opaque at a random sample.
  std::vector<float> t_c(size_t(R) * S), w_c(size_t(R) * S);
  for (int r = 0; r < R; ++r) {
    const int hit = int(rng.next_u64() % uint64_t(S + 3));
    float trans = 1.0f;
    for (int j = 0; j < S; ++j) {
      t_c[size_t(r) * S + j] = 0.1f + 0.2f * j;
      const float alpha = j == hit ? 0.99999f : (j > hit ? 0.5f : 0.02f);
      w_c[size_t(r) * S + j] = trans * alpha;
      trans *= 1.0f - alpha;
    }
  }
  auto btc = cl::Buffer::from(rt, t_c), bwc = cl::Buffer::from(rt, w_c);
  cl::Buffer bx(rt, size_t(R) * M * 3 * 4);
  bx.fill_zero();
  pipeline::SampleCompaction live(rt, R, M, S, 3, eps);
  const int n_live = int(live.select(R, M, btc, bwc, btc, bx));
  const auto live_off = live.offsets().read_vec<int32_t>(size_t(R) + 1);
  REQUIRE(n_live < R * M);
  // Weights (full layout) with a random band above thr, and the live rows' density output.
  std::vector<float> w(size_t(R) * M), dens(size_t(n_live) * stride);
  for (auto& v : w)
    v = rng.uniform(0, 1) < 0.3f ? rng.uniform(0.0f, 0.5f) : rng.uniform(0.0f, 0.9f * thr);
  for (auto& v : dens) v = rng.uniform(-1, 1);
  auto bw = cl::Buffer::from(rt, w), bdens = cl::Buffer::from(rt, dens);
  pipeline::HeadBand band(rt, R + 4, M, thr);  // capacity above the call
  const long n_band = band.select(R, M, live, bw, bdens);
  std::vector<int32_t> begin, count, band_off{0}, ray_ref;
  int empty = 0;
  for (int r = 0; r < R; ++r) {
    int first = -1, last = -1;
    for (int s = 0; s < live_off[size_t(r) + 1] - live_off[size_t(r)]; ++s)
      if (w[size_t(r) * M + s] > thr) {
        if (first < 0) first = s;
        last = s;
      }
    begin.push_back(first < 0 ? 0 : first);
    count.push_back(first < 0 ? 0 : last - first + 1);
    band_off.push_back(band_off.back() + count.back());
    for (int i = 0; i < count.back(); ++i) ray_ref.push_back(r);
    empty += count.back() == 0;
  }
  CHECK(empty > 0);
  CHECK(n_band == band_off.back());
  CHECK(n_band < n_live);
  const field::GroupIndex index = band.index(R);
  CHECK(index.n_groups == R);
  CHECK(index.offsets->read_vec<int32_t>(size_t(R) + 1) == band_off);
  CHECK(index.point_group->read_vec<int32_t>(size_t(n_band)) == ray_ref);
  std::vector<float> dens_ref;
  for (int r = 0; r < R; ++r)
    for (int i = 0; i < count[size_t(r)]; ++i)
      for (int k = 0; k < stride; ++k)
        dens_ref.push_back(dens[size_t(live_off[size_t(r)] + begin[size_t(r)] + i) * stride + k]);
  CHECK(band.density().read_vec<float>(dens_ref.size()) == dens_ref);

  // The head's outputs into the full layout (−30 outside the band).
  std::vector<float> head_b(size_t(n_band) * 2);
  for (auto& v : head_b) v = rng.uniform(-3, 3);
  band.head_out().write_vec(head_b);
  auto bhead = cl::Buffer::from(rt, std::vector<float>(size_t(R) * M * 2, 9.0f));
  band.expand_head(R, M, bhead);
  std::vector<float> head_ref(size_t(R) * M * 2, -30.0f);
  for (int r = 0; r < R; ++r)
    for (int i = 0; i < count[size_t(r)]; ++i) {
      const size_t q = size_t(r) * M + size_t(begin[size_t(r)] + i);
      const size_t row = size_t(band_off[size_t(r)] + i);
      head_ref[2 * q] = head_b[2 * row];
      head_ref[2 * q + 1] = head_b[2 * row + 1];
    }
  CHECK(bhead.read_vec<float>(head_ref.size()) == head_ref);

  // Backward: dL/dhead's band rows, and the head's input gradient into the live rows.
  std::vector<float> g_head(size_t(R) * M * 2), g_dens_b(size_t(n_band) * stride);
  for (auto& v : g_head) v = rng.uniform(-1, 1);
  for (auto& v : g_dens_b) v = rng.uniform(-1, 1);
  auto bghead = cl::Buffer::from(rt, g_head);
  band.gather_head_gradient(R, M, live, bghead);
  std::vector<float> gh_ref;
  for (int r = 0; r < R; ++r)
    for (int i = 0; i < count[size_t(r)]; ++i)
      for (int k = 0; k < 2; ++k)
        gh_ref.push_back(g_head[(size_t(r) * M + size_t(begin[size_t(r)] + i)) * 2 + k]);
  CHECK(band.grad_head().read_vec<float>(gh_ref.size()) == gh_ref);
  band.grad_density().write_vec(g_dens_b);
  auto bgdens = cl::Buffer::from(rt, std::vector<float>(size_t(R) * M * stride, 5.0f));
  band.scatter_density_gradient(R, M, live, bgdens);
  std::vector<float> gd_ref(size_t(R) * M * stride, 5.0f);  // rows past the live ones untouched
  std::fill(gd_ref.begin(), gd_ref.begin() + size_t(n_live) * stride, 0.0f);
  for (int r = 0; r < R; ++r)
    for (int i = 0; i < count[size_t(r)]; ++i)
      for (int k = 0; k < stride; ++k)
        gd_ref[size_t(live_off[size_t(r)] + begin[size_t(r)] + i) * stride + k] =
            g_dens_b[size_t(band_off[size_t(r)] + i) * stride + k];
  CHECK(bgdens.read_vec<float>(gd_ref.size()) == gd_ref);
}
