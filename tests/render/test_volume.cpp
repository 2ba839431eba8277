// Volume rendering kernels: device vs reference, physical checks (opaque wall, weights sum),
// determinism, and the backward against finite differences of the double-precision forward.
#include <catch2/catch.hpp>
#include <cmath>
#include <numeric>

#include "render/volume_renderer.hpp"
#include "render_reference.hpp"
#include "render_test_data.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {
const float kScale = 0.0125f;

// Sorted jittered t: near + (i + u) * bin, as the uniform sampler makes them.
std::vector<float> make_t(int n_rays, int S, float near, float far, uint64_t seed) {
  const auto u = test::make_uniform(size_t(n_rays) * S, 0.f, 1.f, seed);
  std::vector<float> t(u.size());
  for (size_t s = 0; s < t.size(); ++s) t[s] = near + ((s % S) + u[s]) * (far - near) / S;
  return t;
}

struct Fwd {
  std::vector<float> out, w;
};

Fwd run_fwd(render::VolumeRenderer& vr, const std::vector<float>& t, const std::vector<float>& h0,
            const std::vector<float>& head, int n_rays, int S) {
  auto& rt = test::runtime();
  auto bt = cl::Buffer::from(rt, t), bh = cl::Buffer::from(rt, h0),
       bhead = cl::Buffer::from(rt, head);
  cl::Buffer out(rt, size_t(n_rays) * 12), w(rt, t.size() * 4);
  vr.forward(bt, bh, bhead, n_rays, S, out, w).wait();
  return {out.read_vec<float>(size_t(n_rays) * 3), w.read_vec<float>(t.size())};
}

// The forward, then the median depth on the forward's own weights and outputs.
struct Median {
  Fwd fwd;                 // expected depth, prob, intensity; weights
  std::vector<float> out;  // the same with the median depth
};
Median run_median(render::VolumeRenderer& vr, const std::vector<float>& t,
                  const std::vector<float>& h0, const std::vector<float>& head, int n_rays, int S) {
  auto& rt = test::runtime();
  auto bt = cl::Buffer::from(rt, t), bh = cl::Buffer::from(rt, h0),
       bhead = cl::Buffer::from(rt, head);
  cl::Buffer out(rt, size_t(n_rays) * 12), w(rt, t.size() * 4);
  vr.forward(bt, bh, bhead, n_rays, S, out, w).wait();
  Median m{{out.read_vec<float>(size_t(n_rays) * 3), w.read_vec<float>(t.size())}, {}};
  vr.median_depth(bt, w, n_rays, S, out).wait();
  m.out = out.read_vec<float>(size_t(n_rays) * 3);
  return m;
}
}  // namespace

TEST_CASE(
    "Volume forward (8-sample chunks and a tail) equals the reference, bit-identical when repeated",
    "[render][volume]") {
  render::RenderConfig cfg;
  cfg.n_samples = 67;
  render::VolumeRenderer vr(test::runtime(), cfg, kScale);
  const int n_rays = 257, S = 67;
  const auto t = make_t(n_rays, S, cfg.near_m * kScale, cfg.far_m * kScale, 1);
  const auto h0 = test::make_uniform(t.size(), -2.f, 4.f, 2);
  const auto head = test::make_uniform(2 * t.size(), -4.f, 4.f, 3);
  const auto dev = run_fwd(vr, t, h0, head, n_rays, S);
  std::vector<float> out_ref, w_ref;
  test::ref_volume_fwd<float>(n_rays, S, vr.last_delta(), t, h0, head, out_ref, w_ref);
  CHECK(test::max_sym_rel_err(dev.out, out_ref, 1e-6) < 1e-4);
  CHECK(test::max_sym_rel_err(dev.w, w_ref, 1e-7) < 1e-4);
  const auto again = run_fwd(vr, t, h0, head, n_rays, S);
  CHECK(again.out == dev.out);
  CHECK(again.w == dev.w);

  // The weights-only kernel gives the same weights: the same inline code (volume.cl) on the same
  // device, bit for bit.
  auto& rt = test::runtime();
  auto bt = cl::Buffer::from(rt, t), bh = cl::Buffer::from(rt, h0);
  cl::Buffer w(rt, t.size() * 4);
  vr.weights(bt, bh, n_rays, S, w).wait();
  CHECK(w.read_vec<float>(t.size()) == dev.w);
}

TEST_CASE("An opaque wall at distance D renders depth D and the head's values",
          "[render][volume]") {
  render::RenderConfig cfg;
  cfg.n_samples = 256;
  render::VolumeRenderer vr(test::runtime(), cfg, kScale);
  const int n_rays = 16, S = 256;
  const float near = cfg.near_m * kScale, far = cfg.far_m * kScale;
  const auto t = make_t(n_rays, S, near, far, 4);
  std::vector<float> h0(t.size()), head(2 * t.size());
  std::vector<float> wall(n_rays), logit_p(n_rays), logit_i(n_rays);
  for (int r = 0; r < n_rays; ++r) {
    wall[r] = (5.f + 4.5f * r) * kScale;  // 5 m .. 72.5 m
    logit_p[r] = -2.f + 0.3f * r;
    logit_i[r] = 1.5f - 0.2f * r;
    for (int i = 0; i < S; ++i) {
      const size_t s = size_t(r) * S + i;
      h0[s] = t[s] < wall[r] ? -12.f : 12.f;  // σ ≈ 1.6e5 per unit: opaque within one sample
      head[2 * s] = logit_p[r];
      head[2 * s + 1] = logit_i[r];
    }
  }
  const auto dev = run_fwd(vr, t, h0, head, n_rays, S);
  const float bin = (far - near) / S;
  for (int r = 0; r < n_rays; ++r) {
    const double wsum =
        std::accumulate(dev.w.begin() + size_t(r) * S, dev.w.begin() + size_t(r + 1) * S, 0.0);
    INFO("ray " << r << " wall " << wall[r] / kScale << " m, depth " << dev.out[3 * r] / kScale);
    CHECK(wsum == Approx(1.0).margin(1e-4));
    CHECK(std::abs(dev.out[3 * r] - wall[r]) <= bin);  // the first sample behind the wall
    CHECK(dev.out[3 * r + 1] == Approx(test::ref_sigmoid(logit_p[r])).epsilon(1e-4));
    CHECK(dev.out[3 * r + 2] == Approx(test::ref_sigmoid(logit_i[r])).epsilon(1e-4));
  }
}

TEST_CASE("Median depth equals the reference: where the transmittance falls to 1/2",
          "[render][volume]") {
  render::RenderConfig cfg;
  cfg.n_samples = 67;
  render::VolumeRenderer vr(test::runtime(), cfg, kScale);
  const int n_rays = 257, S = 67;
  const auto t = make_t(n_rays, S, cfg.near_m * kScale, cfg.far_m * kScale, 11);
  // Densities from transparent to opaque, so that some rays never reach 1/2.
  auto h0 = test::make_uniform(t.size(), -6.f, 3.f, 12);
  for (int r = 0; r < n_rays; ++r)
    for (int i = 0; i < S; ++i) h0[size_t(r) * S + i] -= 0.05f * float(r % 40);
  const auto head = test::make_uniform(2 * t.size(), -4.f, 4.f, 13);
  const auto run = run_median(vr, t, h0, head, n_rays, S);
  const auto& expected_out = run.fwd.out;
  const auto& weights = run.fwd.w;
  const auto& med = run.out;
  const auto ref = test::ref_median_depth(n_rays, S, vr.last_delta(), t, weights);
  int never = 0, checked = 0;
  for (int r = 0; r < n_rays; ++r) {
    const int k = ref.index[size_t(r)];
    const size_t s = size_t(r) * S + size_t(k);
    const double delta = k + 1 < S ? double(t[s + 1]) - t[s] : vr.last_delta();
    INFO("ray " << r << " reference index " << k << " weight before " << ref.before[size_t(r)]
                << " depth " << ref.depth[size_t(r)] << " device " << med[3 * r]);
    // Prob and intensity untouched.
    CHECK(med[3 * r + 1] == expected_out[3 * r + 1]);
    CHECK(med[3 * r + 2] == expected_out[3 * r + 2]);
    if (!ref.crossed[size_t(r)]) {
      ++never;
      CHECK(med[3 * r] == t[size_t(r) * S + S - 1]);
      continue;
    }
    // Where the float and double running sums could straddle 1/2, the sample may differ.
    if (ref.before[size_t(r)] + weights[s] < 0.5 + 1e-5) continue;  // (never-ray in float)
    if (std::abs(ref.before[size_t(r)] + weights[s] - 0.5) < 1e-5) continue;
    ++checked;
    CHECK(med[3 * r] >= t[s]);
    CHECK(med[3 * r] <= t[s] + delta * (1 + 1e-5));
    CHECK(std::abs(med[3 * r] - ref.depth[size_t(r)]) <= 1e-3 * delta + 1e-6);
  }
  CHECK(never > 10);            // rays whose weights stay below 1/2: the last sample's t
  CHECK(n_rays - never > 100);  // and rays with a crossing
  CHECK(checked > n_rays - never - 5);
}

TEST_CASE("Depth spread equals the reference: opacity and weight-normalised variance",
          "[render][volume]") {
  render::RenderConfig cfg;
  cfg.n_samples = 45;
  render::VolumeRenderer vr(test::runtime(), cfg, kScale);
  const int n_rays = 130, S = 45;
  const auto t = make_t(n_rays, S, cfg.near_m * kScale, cfg.far_m * kScale, 21);
  auto h0 = test::make_uniform(t.size(), -6.f, 3.f, 22);
  for (int i = 0; i < S; ++i) h0[i] = -40.0f;  // ray 0 empty: opacity 0, variance 0
  const std::vector<float> head(2 * t.size(), 0.0f);
  const Fwd f = run_fwd(vr, t, h0, head, n_rays, S);
  auto& rt = test::runtime();
  auto bt = cl::Buffer::from(rt, t), bw = cl::Buffer::from(rt, f.w);
  cl::Buffer stats(rt, size_t(n_rays) * 8);
  vr.depth_spread(bt, bw, n_rays, S, stats).wait();
  const auto dev = stats.read_vec<float>(size_t(n_rays) * 2);
  const auto ref = test::ref_depth_spread(n_rays, S, t, f.w);
  CHECK(dev[0] < 1e-12f);
  CHECK(dev[1] == 0.0f);
  double max_v = 0;
  for (int r = 0; r < n_rays; ++r) {
    CHECK(dev[2 * r] == Approx(ref[2 * r]).margin(1e-6));
    CHECK(dev[2 * r + 1] == Approx(ref[2 * r + 1]).epsilon(1e-3).margin(1e-8));
    max_v = std::max(max_v, ref[2 * r + 1]);
  }
  CHECK(max_v > 1e-3);  // spread rays exist in the test field
  // An opaque wall: all the weight in one sample, no spread.
  std::vector<float> h_wall(t.size(), -40.0f);
  for (int r = 0; r < n_rays; ++r) h_wall[size_t(r) * S + 20] = 12.0f;
  const Fwd wall = run_fwd(vr, t, h_wall, head, n_rays, S);
  bw = cl::Buffer::from(rt, wall.w);
  vr.depth_spread(bt, bw, n_rays, S, stats).wait();
  const auto dw = stats.read_vec<float>(size_t(n_rays) * 2);
  for (int r = 0; r < n_rays; ++r) {
    CHECK(dw[2 * r] == Approx(1.0).margin(1e-5));
    CHECK(dw[2 * r + 1] < 1e-9f);
  }
}

TEST_CASE("Median depth in a homogeneous medium is ln 2 / sigma behind its start",
          "[render][volume]") {
  render::RenderConfig cfg;
  cfg.n_samples = 64;
  render::VolumeRenderer vr(test::runtime(), cfg, kScale);
  const int n_rays = 6, S = 64;
  const auto t = make_t(n_rays, S, cfg.near_m * kScale, cfg.far_m * kScale, 15);
  std::vector<float> h0(t.size()), head(2 * t.size(), 0.f);
  std::vector<double> half(n_rays);
  for (int r = 0; r < n_rays; ++r) {
    half[r] = (3.0 + 7.3 * r) * kScale;  // transmittance 1/2 at 3 m .. 39.5 m into the medium
    for (int i = 0; i < S; ++i) h0[size_t(r) * S + i] = float(std::log(std::log(2.0) / half[r]));
  }
  const auto med = run_median(vr, t, h0, head, n_rays, S).out;
  for (int r = 0; r < n_rays; ++r) {
    INFO("ray " << r);
    // The medium starts at the first sample; between samples the quadrature is exact.
    CHECK(med[3 * r] == Approx(t[size_t(r) * S] + half[r]).epsilon(2e-5));
  }
}

TEST_CASE("Median depth: a half-opaque foreground never blends with the wall behind it",
          "[render][volume]") {
  // Expected depth averages a translucent edge with the background; the median picks one.
  render::RenderConfig cfg;
  cfg.n_samples = 256;
  render::VolumeRenderer vr(test::runtime(), cfg, kScale);
  const int n_rays = 8, S = 256;
  const float near = cfg.near_m * kScale, far = cfg.far_m * kScale, bin = (far - near) / S;
  const auto t = make_t(n_rays, S, near, far, 14);
  std::vector<float> h0(t.size(), -12.f), head(2 * t.size(), 0.f);
  const float fg = 10.f * kScale, bg = 30.f * kScale;
  std::vector<float> opacity(n_rays);
  for (int r = 0; r < n_rays; ++r) {
    opacity[r] = 0.1f + 0.8f * float(r) / float(n_rays - 1);  // 0.1 .. 0.9
    bool first = true;
    for (int i = 0; i < S; ++i) {
      const size_t s = size_t(r) * S + i;
      const float delta = i + 1 < S ? t[s + 1] - t[s] : vr.last_delta();
      if (t[s] >= fg && first) {  // one sample with α = opacity
        h0[s] = std::log(-std::log(1.f - opacity[r]) / delta);
        first = false;
      } else if (t[s] >= bg) {
        h0[s] = 12.f;
      }
    }
  }
  const auto run = run_median(vr, t, h0, head, n_rays, S);
  const auto& mean = run.fwd.out;
  const auto& med = run.out;
  for (int r = 0; r < n_rays; ++r) {
    INFO("ray " << r << " opacity " << opacity[r] << ": expected depth " << mean[3 * r] / kScale
                << " m, median " << med[3 * r] / kScale << " m");
    const float expected = opacity[r] * fg + (1.f - opacity[r]) * bg;
    CHECK(std::abs(mean[3 * r] - expected) <= 2 * bin);
    CHECK(std::abs(med[3 * r] - (opacity[r] >= 0.5f ? fg : bg)) <= 2 * bin);  // jittered t, + interval
  }
}

TEST_CASE("A Gaussian density bump gives weights in [0, 1] summing to at most 1",
          "[render][volume]") {
  render::RenderConfig cfg;
  cfg.n_samples = 128;
  render::VolumeRenderer vr(test::runtime(), cfg, kScale);
  const int n_rays = 64, S = 128;
  const float near = cfg.near_m * kScale, far = cfg.far_m * kScale;
  const auto t = make_t(n_rays, S, near, far, 5);
  std::vector<float> h0(t.size()), head(2 * t.size(), 0.f);
  for (int r = 0; r < n_rays; ++r)
    for (int i = 0; i < S; ++i) {
      const size_t s = size_t(r) * S + i;
      const float c = (10.f + r) * kScale, width = 2.f * kScale;
      const float peak = 0.1f * r;  // from almost transparent to nearly opaque
      h0[s] = std::log(1e-3f + peak / kScale * std::exp(-0.5f * std::pow((t[s] - c) / width, 2.f)));
    }
  const auto dev = run_fwd(vr, t, h0, head, n_rays, S);
  double prev_sum = -1;
  for (int r = 0; r < n_rays; ++r) {
    double wsum = 0;
    for (int i = 0; i < S; ++i) {
      const float w = dev.w[size_t(r) * S + i];
      REQUIRE(w >= 0.f);
      REQUIRE(w <= 1.f);
      wsum += w;
    }
    CHECK(wsum <= 1.0 + 1e-6);
    CHECK(wsum >= prev_sum - 1e-6);  // opacity grows with the bump's height
    CHECK(dev.out[3 * r + 1] == Approx(0.5 * wsum).margin(1e-5));  // sigmoid(0) = 0.5
    prev_sum = wsum;
  }
  CHECK(prev_sum > 0.99);
}

TEST_CASE("Volume backward equals the reference and finite differences", "[render][volume]") {
  auto& rt = test::runtime();
  render::RenderConfig cfg;
  cfg.n_samples = 21;
  render::VolumeRenderer vr(rt, cfg, kScale);
  const int n_rays = 9, S = 21;
  const auto t = make_t(n_rays, S, cfg.near_m * kScale, cfg.far_m * kScale, 6);
  const auto h0 = test::make_uniform(t.size(), 0.f, 4.f, 7);
  const auto head = test::make_uniform(2 * t.size(), -3.f, 3.f, 8);
  const auto g = test::make_uniform(3 * size_t(n_rays), -1.f, 1.f, 9);
  const auto fwd = run_fwd(vr, t, h0, head, n_rays, S);
  auto bt = cl::Buffer::from(rt, t), bh = cl::Buffer::from(rt, h0),
       bhead = cl::Buffer::from(rt, head), bw = cl::Buffer::from(rt, fwd.w),
       bg = cl::Buffer::from(rt, g);
  cl::Buffer gh0(rt, t.size() * 4), ghead(rt, t.size() * 8);
  vr.backward(bt, bh, bhead, bw, bg, n_rays, S, gh0, ghead).wait();
  const auto dev_h0 = gh0.read_vec<float>(t.size());
  const auto dev_head = ghead.read_vec<float>(2 * t.size());
  vr.backward(bt, bh, bhead, bw, bg, n_rays, S, gh0, ghead).wait();
  CHECK(gh0.read_vec<float>(t.size()) == dev_h0);  // bit-identical when repeated
  CHECK(ghead.read_vec<float>(2 * t.size()) == dev_head);

  std::vector<float> ref_h0, ref_head;
  test::ref_volume_bwd<float>(n_rays, S, vr.last_delta(), t, h0, head, g, ref_h0, ref_head);
  CHECK(test::max_sym_rel_err(dev_h0, ref_h0, 1e-6) < 1e-3);
  CHECK(test::max_sym_rel_err(dev_head, ref_head, 1e-7) < 1e-4);

  // Central differences of L = g · out(h0, head) in double.
  std::vector<float> fd_h0, fd_head;
  test::fd_volume_grads(n_rays, S, vr.last_delta(), t, h0, head, g, fd_h0, fd_head);
  // Floors at 1e-4 of the largest gradient: the central differences of a loss of size ~1
  // carry ~1e-10 of rounding noise, which entries far below the largest cannot resolve.
  auto floor_of = [](const std::vector<float>& v) {
    double m = 0;
    for (float x : v) m = std::max(m, double(std::abs(x)));
    return 1e-4 * m;
  };
  CHECK(test::max_sym_rel_err(dev_h0, fd_h0, floor_of(fd_h0)) < 1e-3);
  CHECK(test::max_sym_rel_err(dev_head, fd_head, floor_of(fd_head)) < 1e-3);
}

TEST_CASE("trunc_exp clamps the density gradient's exponent at 15", "[render][volume]") {
  auto& rt = test::runtime();
  render::RenderConfig cfg;
  cfg.n_samples = 4;
  render::VolumeRenderer vr(rt, cfg, kScale);
  // Sample 0 has h0 = 16 over a tiny interval (σδ ≈ 0.9), so its gradient is far from zero
  // and the clamp shows: the kernel uses exp(15) where exp(16) is the true derivative.
  const std::vector<float> t = {0.02f, 0.0200001f, 0.3f, 0.6f};
  const std::vector<float> h0 = {16.f, -30.f, 1.f, 1.f}, head(8, 0.5f), g = {1.f, 0.f, 0.f};
  auto bt = cl::Buffer::from(rt, t), bh = cl::Buffer::from(rt, h0),
       bhead = cl::Buffer::from(rt, head), bg = cl::Buffer::from(rt, g);
  cl::Buffer out(rt, 12), w(rt, 16), gh0(rt, 16), ghead(rt, 32);
  vr.forward(bt, bh, bhead, 1, 4, out, w);
  vr.backward(bt, bh, bhead, w, bg, 1, 4, gh0, ghead).wait();
  const auto dev = gh0.read_vec<float>(4);
  std::vector<float> ref_h0, ref_head;
  test::ref_volume_bwd<float>(1, 4, vr.last_delta(), t, h0, head, g, ref_h0, ref_head);
  CHECK(test::max_sym_rel_err(dev, ref_h0, 1e-12) < 1e-3);
  // The true derivative by central differences in double.
  std::vector<double> td(t.begin(), t.end()), hd(h0.begin(), h0.end()),
      headd(head.begin(), head.end());
  auto depth = [&]() {
    std::vector<double> o, ww;
    test::ref_volume_fwd<double>(1, 4, vr.last_delta(), td, hd, headd, o, ww);
    return o[0];
  };
  hd[0] = 16.0 + 1e-6;
  const double dp = depth();
  hd[0] = 16.0 - 1e-6;
  const double dm = depth();
  const double true_grad = (dp - dm) / 2e-6;
  REQUIRE(std::abs(true_grad) > 1e-3);
  CHECK(dev[0] / true_grad == Approx(std::exp(-1.0)).epsilon(1e-3));
}
