// Device-vs-reference tests of kernels/pipeline/coarse_waves.cl (pipeline::CoarseWaves): the
// per-ray done flags, the wave gather and scatter, and the fill.
#include <catch2/catch.hpp>

#include "core/rng.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

TEST_CASE("coarse wave kernels match the host reference",
          "[pipeline][coarse-waves][device]") {
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
  auto done_k = rt.kernel("pipeline/coarse_waves.cl", "pipeline_wave_done");
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
  rt.kernel("pipeline/coarse_waves.cl", "pipeline_wave_gather")
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
  rt.kernel("pipeline/coarse_waves.cl", "pipeline_wave_scatter")
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
  rt.kernel("pipeline/coarse_waves.cl", "pipeline_fill").set_args(70, -3.5f, bf).launch({128}, {64}).wait();
  CHECK(bf.read_vec<float>(70) == std::vector<float>(70, -3.5f));
}
