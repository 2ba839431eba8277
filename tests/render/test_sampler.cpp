// Ray sampling kernels vs the host reference: uniform stratified (jitter, midpoints,
// determinism), importance sampling (inverse CDF, merged sorted) and the clamp of sample
// positions to the scene box.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>

#include "cl/device_profile.hpp"
#include "render/ray_sampler.hpp"
#include "render/volume_renderer.hpp"
#include "render_reference.hpp"
#include "render_test_data.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {
const float kScale = 0.0125f;  // 1 / 80 m

struct Sampled {
  std::vector<float> t, x;
};

Sampled run_uniform(render::RaySampler& s, const std::vector<float>& o, const std::vector<float>& d,
                    int n_rays, bool jitter, uint64_t seed, uint32_t step) {
  auto& rt = test::runtime();
  auto bo = cl::Buffer::from(rt, o), bd = cl::Buffer::from(rt, d);
  const size_t n = size_t(n_rays) * s.uniform_samples();
  cl::Buffer bt(rt, n * 4), bx(rt, n * 12);
  s.uniform(bo, bd, n_rays, jitter, seed, step, bt, bx).wait();
  return {bt.read_vec<float>(n), bx.read_vec<float>(3 * n)};
}
}  // namespace

TEST_CASE("Uniform jittered samples equal the reference and stay in their bins",
          "[render][sample]") {
  render::RenderConfig cfg;
  cfg.n_samples = 48;
  render::RaySampler sampler(test::runtime(), cfg, kScale);
  const int n_rays = 300;
  std::vector<float> o, d;
  test::make_rays(n_rays, 1, o, d);
  const uint64_t seed = 0xabcdef0123ull;
  const auto dev = run_uniform(sampler, o, d, n_rays, true, seed, 7);
  std::vector<float> t_ref, x_ref;
  test::ref_sample_uniform(n_rays, cfg.n_samples, sampler.near(), sampler.far(), true, seed, 7, o,
                           d, t_ref, x_ref);
  CHECK(test::max_abs_err(dev.t, t_ref) < 1e-6);
  CHECK(test::max_abs_err(dev.x, x_ref) < 1e-6);

  const float bin = (sampler.far() - sampler.near()) / cfg.n_samples;
  size_t outside = 0;
  double mean_frac = 0;
  for (size_t s = 0; s < dev.t.size(); ++s) {
    const int i = int(s % cfg.n_samples);
    const float lo = sampler.near() + i * bin;
    outside += dev.t[s] < lo - 1e-6f || dev.t[s] > lo + bin + 1e-6f;
    mean_frac += (dev.t[s] - lo) / bin;
  }
  CHECK(outside == 0);
  CHECK(mean_frac / dev.t.size() == Approx(0.5).margin(0.02));  // jitter is uniform

  // Same (seed, step): bit-identical; another step: different.
  const auto again = run_uniform(sampler, o, d, n_rays, true, seed, 7);
  CHECK(again.t == dev.t);
  CHECK(again.x == dev.x);
  const auto other = run_uniform(sampler, o, d, n_rays, true, seed, 8);
  CHECK(other.t != dev.t);
}

TEST_CASE("Uniform samples without jitter are the bin midpoints; partial quads match",
          "[render][sample]") {
  render::RenderConfig cfg;
  cfg.n_samples = 15;  // not a multiple of 4: every ray ends in a partial quad
  render::RaySampler sampler(test::runtime(), cfg, kScale);
  std::vector<float> o, d;
  test::make_rays(5, 2, o, d);
  const auto dev = run_uniform(sampler, o, d, 5, false, 1, 0);
  const float bin = (sampler.far() - sampler.near()) / cfg.n_samples;
  for (size_t s = 0; s < dev.t.size(); ++s)
    REQUIRE(dev.t[s] == Approx(sampler.near() + (s % 15 + 0.5f) * bin).epsilon(1e-6));
  CHECK(sampler.near() == Approx(1.0f * kScale));
  CHECK(sampler.far() == Approx(81.0f * kScale));
  const auto jit = run_uniform(sampler, o, d, 5, true, 3, 2);
  std::vector<float> t_ref, x_ref;
  test::ref_sample_uniform(5, 15, sampler.near(), sampler.far(), true, 3, 2, o, d, t_ref, x_ref);
  CHECK(test::max_abs_err(jit.t, t_ref) < 1e-6);
  CHECK(test::max_abs_err(jit.x, x_ref) < 1e-6);
}

TEST_CASE("Importance samples equal the reference, are sorted and follow the weights",
          "[render][sample]") {
  auto& rt = test::runtime();
  render::RenderConfig cfg;
  cfg.n_samples = 32;
  cfg.n_importance = 24;
  // The per-ray kernel, the reference's walk (the cpu profile's, whatever the test's profile):
  // the gpu profile's sums the CDF in another order, which moves samples by more than 1e-5 in
  // light bins; it is held to that rounding's bound in test_sampler_wide.cpp.
  std::unique_ptr<render::RaySampler> made;
  {
    test::ProfileScope scope(cl::cpu_profile());
    made = std::make_unique<render::RaySampler>(rt, cfg, kScale);
  }
  render::RaySampler& sampler = *made;
  const int n_rays = 200, Sc = 32, Sf = 24, So = Sc + Sf;
  std::vector<float> o, d;
  test::make_rays(n_rays, 3, o, d);
  const auto coarse = run_uniform(sampler, o, d, n_rays, true, 5, 1);
  // Weights: a peak in bin (r % Sc) holding ~90 % of the mass, small noise elsewhere.
  auto w = test::make_uniform(size_t(n_rays) * Sc, 0.0f, 0.004f, 4);
  for (int r = 0; r < n_rays; ++r) w[size_t(r) * Sc + r % Sc] = 0.9f;
  auto bo = cl::Buffer::from(rt, o), bd = cl::Buffer::from(rt, d);
  auto btc = cl::Buffer::from(rt, coarse.t), bwc = cl::Buffer::from(rt, w);
  cl::Buffer bt(rt, size_t(n_rays) * So * 4), bx(rt, size_t(n_rays) * So * 12),
      bsrc(rt, size_t(n_rays) * So * 4);
  for (bool jitter : {true, false}) {
    sampler.importance(bo, bd, n_rays, Sc, btc, bwc, jitter, 99, 3, bt, bx, bsrc).wait();
    const auto t = bt.read_vec<float>(size_t(n_rays) * So);
    const auto x = bx.read_vec<float>(size_t(n_rays) * So * 3);
    const auto src = bsrc.read_vec<int>(size_t(n_rays) * So);
    std::vector<float> t_ref, x_ref;
    std::vector<int> src_ref;
    test::ref_sample_importance(n_rays, Sc, Sf, sampler.near(), sampler.far(), jitter, 99, 3, o, d,
                                coarse.t, w, t_ref, x_ref, &src_ref);
    CHECK(test::max_abs_err(t, t_ref) < 1e-5);
    CHECK(test::max_abs_err(x, x_ref) < 1e-5);
    // Sources: the reference's, and each coarse source returns that coarse sample's t exactly.
    size_t src_mismatch = 0, coarse_t_mismatch = 0;
    for (size_t s = 0; s < src.size(); ++s) {
      src_mismatch += src[s] != src_ref[s];
      if (src[s] >= 0 && src[s] < Sc)
        coarse_t_mismatch += t[s] != coarse.t[s / So * Sc + size_t(src[s])];
    }
    CHECK(src_mismatch == 0);
    CHECK(coarse_t_mismatch == 0);
    size_t unsorted = 0, in_peak = 0, fine_total = 0;
    for (int r = 0; r < n_rays; ++r) {
      const float* tr = &t[size_t(r) * So];
      unsorted += !std::is_sorted(tr, tr + So);
      // The peak bin lies between the midpoints around coarse sample k = r % Sc.
      const int k = r % Sc;
      const float* tc = &coarse.t[size_t(r) * Sc];
      const float lo = k == 0 ? sampler.near() : 0.5f * (tc[k - 1] + tc[k]);
      const float hi = k == Sc - 1 ? sampler.far() : 0.5f * (tc[k] + tc[k + 1]);
      for (int i = 0; i < So; ++i) in_peak += tr[i] >= lo && tr[i] <= hi;
      in_peak -= 1;  // the coarse sample itself
      fine_total += Sf;
    }
    CHECK(unsorted == 0);
    // The peak holds 0.9 / (0.9 + 31 * 0.002 + 32e-5) ≈ 93.5 % of the probability.
    CHECK(double(in_peak) / fine_total > 0.88);
    CHECK(double(in_peak) / fine_total < 0.99);
  }
}

TEST_CASE("Coarse weights of an opaque wall draw the importance samples to the wall",
          "[render][sample]") {
  auto& rt = test::runtime();
  render::RenderConfig cfg;
  cfg.n_samples = 32;
  cfg.n_importance = 32;
  render::RaySampler sampler(rt, cfg, kScale);
  render::VolumeRenderer vr(rt, cfg, kScale);
  const int n_rays = 20, Sc = 32, So = 64;
  std::vector<float> o, d;
  test::make_rays(n_rays, 4, o, d);
  const auto coarse = run_uniform(sampler, o, d, n_rays, true, 8, 0);
  std::vector<float> h0(coarse.t.size()), wall(n_rays);
  for (int r = 0; r < n_rays; ++r) {
    wall[r] = (8.f + 3.f * r) * kScale;
    for (int i = 0; i < Sc; ++i) h0[r * Sc + i] = coarse.t[r * Sc + i] < wall[r] ? -10.f : 10.f;
  }
  auto bo = cl::Buffer::from(rt, o), bd = cl::Buffer::from(rt, d);
  auto btc = cl::Buffer::from(rt, coarse.t), bh = cl::Buffer::from(rt, h0);
  cl::Buffer w(rt, coarse.t.size() * 4), bt(rt, size_t(n_rays) * So * 4),
      bx(rt, size_t(n_rays) * So * 12), bsrc(rt, size_t(n_rays) * So * 4);
  vr.weights(btc, bh, n_rays, Sc, w);
  sampler.importance(bo, bd, n_rays, Sc, btc, w, true, 8, 1, bt, bx, bsrc).wait();
  const auto t = bt.read_vec<float>(size_t(n_rays) * So);
  const float bin = (sampler.far() - sampler.near()) / Sc;
  size_t near_wall = 0;
  for (int r = 0; r < n_rays; ++r) {
    // The first coarse sample behind the wall takes the weight; its bin spans at most one
    // bin width on either side of it, hence 2 bins from the wall.
    for (int i = 0; i < So; ++i) near_wall += std::abs(t[r * So + i] - wall[r]) < 2.f * bin;
  }
  // 32 fine samples per ray, nearly all near the wall, plus 1-4 coarse ones there.
  CHECK(double(near_wall) / (n_rays * 32) > 0.95);
}

TEST_CASE("render_clamp_points matches the host reference", "[render][sample]") {
  auto& rt = test::runtime();
  const int n = 3 * 777;
  std::vector<float> x(n);
  Rng rng(6);
  for (auto& v : x) v = rng.uniform(-3, 3);
  auto bx = cl::Buffer::from(rt, x);
  auto k = rt.kernel("render/sample.cl", "render_clamp_points");
  k.set_args(n, 1.0f, bx).launch({cl::round_up(n, 64)}, {64}).wait();
  const auto y = bx.read_vec<float>(n);
  int clamped = 0;
  for (int i = 0; i < n; ++i) {
    CHECK(y[i] == std::min(1.0f, std::max(-1.0f, x[i])));
    clamped += std::fabs(x[i]) > 1.0f;
  }
  CHECK(clamped > 0);
}
