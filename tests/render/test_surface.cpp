// Training samples placed by the return and the weight-carving loss (kernels/render/surface.cl)
// against their host references: the samples' layout (free space, band, behind; rays without
// a return uniform), determinism, the carving loss and its gradient on the device, and that
// gradient against finite differences of the double-precision loss.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "core/config.hpp"
#include "core/error.hpp"
#include "render/surface_sampler.hpp"
#include "render/volume_renderer.hpp"
#include "render/weight_carving.hpp"
#include "render_test_data.hpp"
#include "support/test_device.hpp"
#include "surface_reference.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {
const float kScale = 0.0125f;  // 1 / 80 m

render::RenderConfig surface_config() {
  render::RenderConfig c;
  c.surface_free_samples = 12;
  c.surface_band_samples = 10;
  c.surface_behind_samples = 3;
  c.surface_band_start_m = 1.0f;
  c.surface_band_end_m = 0.25f;
  c.surface_anneal_steps = 100;
  c.surface_behind_m = 2.0f;
  return c;
}

// Targets (range normalised, intensity, label): every 5th ray without a return, one return
// nearer than near + band.
std::vector<float> make_targets(int n, float near, float far) {
  const auto u = test::make_uniform(size_t(n), 0.f, 1.f, 77);
  std::vector<float> t(size_t(n) * 3);
  for (int r = 0; r < n; ++r) {
    const bool ret = r % 5 != 0;
    t[3 * r] = ret ? near + (0.05f + 0.9f * u[r]) * (far - near) : 0.0f;
    t[3 * r + 1] = 0.3f;
    t[3 * r + 2] = ret ? 1.0f : 0.0f;
  }
  t[3 * 1] = near + 0.2f * kScale;  // a return 0.2 m behind near: its band is cut at near
  return t;
}

struct Sampled {
  std::vector<float> t, x;
};

Sampled run_surface(render::SurfaceSampler& s, const std::vector<float>& o,
                    const std::vector<float>& d, const std::vector<float>& target, int n_rays,
                    bool jitter, uint64_t seed, uint32_t step) {
  auto& rt = test::runtime();
  auto bo = cl::Buffer::from(rt, o), bd = cl::Buffer::from(rt, d), bg = cl::Buffer::from(rt, target);
  const size_t n = size_t(n_rays) * s.samples();
  cl::Buffer bt(rt, n * 4), bx(rt, n * 12);
  s.sample(bo, bd, bg, n_rays, jitter, seed, step, bt, bx).wait();
  return {bt.read_vec<float>(n), bx.read_vec<float>(3 * n)};
}
}  // namespace

TEST_CASE("Surface samples equal the reference: free space, band, behind; no return uniform",
          "[render][surface]") {
  const auto cfg = surface_config();
  render::SurfaceSampler sampler(test::runtime(), cfg, kScale);
  const int n_rays = 200, M = sampler.samples();
  REQUIRE(M == 25);
  std::vector<float> o, d;
  test::make_rays(n_rays, 3, o, d);
  const auto target = make_targets(n_rays, sampler.near(), sampler.far());
  const uint64_t seed = 0x5eed5eedull;
  const uint32_t step = 40;
  const auto dev = run_surface(sampler, o, d, target, n_rays, true, seed, step);
  const float w = sampler.half_width(step);
  CHECK(w == Approx(0.25 * std::pow(4.0, 0.6) * kScale).epsilon(1e-5));  // 1 m → 0.25 m, 40 %
  std::vector<float> t_ref, x_ref;
  test::ref_sample_surface(n_rays, 12, 10, 3, sampler.near(), sampler.far(), w,
                           cfg.surface_behind_m * kScale, true, seed, step, o, d, target, t_ref,
                           x_ref);
  CHECK(test::max_abs_err(dev.t, t_ref) < 1e-6);
  CHECK(test::max_abs_err(dev.x, x_ref) < 1e-6);

  // The layout: sorted; the band's samples within ±w of the return, the free ones in front.
  int unsorted = 0, out_of_band = 0, free_behind = 0, uniform_off = 0;
  for (int r = 0; r < n_rays; ++r) {
    const float rr = target[3 * r];
    for (int i = 0; i < M; ++i) {
      const float v = dev.t[size_t(r) * M + i];
      if (i > 0 && v < dev.t[size_t(r) * M + i - 1]) ++unsorted;
      if (target[3 * r + 2] < 0.5f) {  // no return: bin i of M over [near, far]
        const float bin = (sampler.far() - sampler.near()) / M;
        uniform_off += v < sampler.near() + i * bin - 1e-6f || v > sampler.near() + (i + 1) * bin + 1e-6f;
        continue;
      }
      if (i >= 12 && i < 22) out_of_band += std::abs(v - rr) > w + 1e-6f;
      if (i < 12) free_behind += v > rr - w + 1e-6f && v > sampler.near() + 1e-6f;
    }
  }
  CHECK(unsorted == 0);
  CHECK(out_of_band == 0);
  CHECK(free_behind == 0);
  CHECK(uniform_off == 0);
  // Behind the return: within [r + w, r + w + behind], the last one beyond, up to far.
  const float rr = target[3 * 2];
  REQUIRE(rr + w + 2.0f * kScale < sampler.far());
  for (int i = 22; i < 24; ++i) {
    CHECK(dev.t[size_t(2) * M + i] >= rr + w - 1e-6f);
    CHECK(dev.t[size_t(2) * M + i] <= rr + w + 2.0f * kScale + 1e-6f);
  }
  CHECK(dev.t[size_t(2) * M + 24] >= rr + w + 2.0f * kScale - 1e-6f);
  CHECK(dev.t[size_t(2) * M + 24] <= sampler.far());

  // Same seed and step: bit-identical; another step: other jitter; no jitter: the reference.
  CHECK(run_surface(sampler, o, d, target, n_rays, true, seed, step).t == dev.t);
  CHECK(run_surface(sampler, o, d, target, n_rays, true, seed, step + 1).t != dev.t);
  const auto mid = run_surface(sampler, o, d, target, n_rays, false, 0, step);
  test::ref_sample_surface(n_rays, 12, 10, 3, sampler.near(), sampler.far(), w,
                           cfg.surface_behind_m * kScale, false, 0, step, o, d, target, t_ref,
                           x_ref);
  CHECK(test::max_abs_err(mid.t, t_ref) < 1e-6);
}

TEST_CASE("The band narrows log-linearly and the config refuses a widening band",
          "[render][surface]") {
  auto cfg = surface_config();
  CHECK(cfg.surface_band_m(0) == Approx(1.0f));
  CHECK(cfg.surface_band_m(50) == Approx(0.5f).epsilon(1e-5));
  CHECK(cfg.surface_band_m(100) == Approx(0.25f));
  CHECK(cfg.surface_band_m(100000) == Approx(0.25f));
  cfg.surface_band_end_m = 2.0f;
  CHECK_THROWS_AS(cfg.validate(), ConfigError);
  render::RenderConfig off;
  CHECK_THROWS_AS(render::SurfaceSampler(test::runtime(), off, kScale), Error);
  // Off by default: no surface key is written (configs and their hashes stay as they were).
  const std::string j = off.to_json().dump();
  CHECK(j.find("surface") == std::string::npos);
  CHECK(j.find("carve") == std::string::npos);
}

TEST_CASE("Weight carving equals the reference and finite differences", "[render][surface]") {
  auto cfg = surface_config();
  cfg.n_samples = 64;  // the last sample's δ is the 64-sample bin width
  cfg.weights.carve = 3.0f;
  auto& rt = test::runtime();
  render::SurfaceSampler sampler(rt, cfg, kScale);
  render::VolumeRenderer vr(rt, cfg, kScale);
  const int n_rays = 60, M = sampler.samples();
  render::WeightCarving carving(rt, cfg, kScale, n_rays);
  std::vector<float> o, d;
  test::make_rays(n_rays, 5, o, d);
  const auto target = make_targets(n_rays, sampler.near(), sampler.far());
  const auto s = run_surface(sampler, o, d, target, n_rays, true, 9, 10);
  // σ logits that put density in front of, at and behind the returns.
  const auto h0 = test::make_uniform(s.t.size(), -1.0f, 3.0f, 13);
  const std::vector<float> head(s.t.size() * 2, 0.0f);
  const float w = sampler.half_width(10), last = cfg.bin_width(kScale);

  auto bt = cl::Buffer::from(rt, s.t), bh = cl::Buffer::from(rt, h0),
       bhead = cl::Buffer::from(rt, head), bg = cl::Buffer::from(rt, target);
  cl::Buffer out(rt, size_t(n_rays) * 12), bw(rt, s.t.size() * 4);
  vr.forward(bt, bh, bhead, n_rays, M, out, bw).wait();
  // The kernel ADDS to g_h0: start from a known gradient.
  const std::vector<float> g0(s.t.size(), 0.5f);
  auto bgh = cl::Buffer::from(rt, g0);
  carving.add(bt, bh, bw, bg, n_rays, M, w, bgh).wait();
  auto g_dev = bgh.read_vec<float>(s.t.size());
  for (auto& v : g_dev) v -= 0.5f;

  const double scale = cfg.weights.carve / n_rays;
  const std::vector<double> td(s.t.begin(), s.t.end()), hd(h0.begin(), h0.end());
  std::vector<double> terms;
  const double loss = test::ref_carve_loss<double>(n_rays, M, last, sampler.near(), w, scale, td,
                                                   hd, target, &terms);
  CHECK(loss > 1e-3);  // the test field is translucent enough to carve
  CHECK(carving.read() == Approx(loss).epsilon(1e-4));
  const auto g_ref =
      test::ref_carve_grad<double>(n_rays, M, last, sampler.near(), w, scale, td, hd, target);
  double max_ref = 0, max_err = 0;
  for (size_t i = 0; i < g_ref.size(); ++i) {
    max_ref = std::max(max_ref, std::abs(g_ref[i]));
    max_err = std::max(max_err, std::abs(g_ref[i] - double(g_dev[i])));
  }
  CHECK(max_ref > 1e-4);
  CHECK(max_err < 1e-4 * max_ref + 1e-7);

  // Finite differences of the double loss on a spread of samples.
  int checked = 0;
  for (size_t i = 3; i < hd.size(); i += 37) {
    auto hp = hd, hm = hd;
    const double eps = 1e-5;
    hp[i] += eps, hm[i] -= eps;
    const double fd = (test::ref_carve_loss<double>(n_rays, M, last, sampler.near(), w, scale, td,
                                                    hp, target) -
                       test::ref_carve_loss<double>(n_rays, M, last, sampler.near(), w, scale, td,
                                                    hm, target)) /
                      (2 * eps);
    CHECK(std::abs(fd - g_ref[i]) < 1e-6 + 1e-4 * std::abs(fd));
    ++checked;
  }
  CHECK(checked > 30);
  // Rays without a return carry no loss and no gradient.
  for (int i = 0; i < M; ++i) CHECK(g_dev[size_t(5) * M + i] == 0.0f);
}

TEST_CASE("Carving an opaque wall at the return costs nothing; a fog in front costs",
          "[render][surface]") {
  auto cfg = surface_config();
  cfg.weights.carve = 1.0f;
  auto& rt = test::runtime();
  render::SurfaceSampler sampler(rt, cfg, kScale);
  const int n_rays = 2, M = sampler.samples();
  std::vector<float> o(6, 0.0f), d = {1, 0, 0, 1, 0, 0};
  const float rr = sampler.near() + 20.0f * kScale;
  const std::vector<float> target = {rr, 0.5f, 1.0f, rr, 0.5f, 1.0f};
  const auto s = run_surface(sampler, o, d, target, n_rays, false, 0, 1000);
  const float w = sampler.half_width(1000), last = cfg.bin_width(kScale);
  std::vector<double> td(s.t.begin(), s.t.end()), h(td.size());
  for (int i = 0; i < M; ++i) {
    h[i] = std::abs(td[i] - rr) <= w ? 12.0 : -30.0;  // ray 0: opaque inside the band only
    h[size_t(M) + i] = td[size_t(M) + i] < rr - w ? 2.0 : 12.0;  // ray 1: fog in front
  }
  std::vector<double> terms;
  test::ref_carve_loss<double>(n_rays, M, last, sampler.near(), w, 1.0, td, h, target, &terms);
  CHECK(terms[0] < 1e-12);
  CHECK(terms[1] > 1e-3);
}
