// Ray gradient reduction vs the reference, and the whole chain dL/d(o, d) (sampling positions
// -> synthetic field -> volume rendering -> backward -> reduction) against finite differences.
#include <catch2/catch.hpp>
#include <cmath>

#include "render/ray_gradient.hpp"
#include "render/ray_sampler.hpp"
#include "render/volume_renderer.hpp"
#include "render_reference.hpp"
#include "render_test_data.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

TEST_CASE("Ray gradient reduction equals the reference", "[render][raygrad]") {
  auto& rt = test::runtime();
  const int n_rays = 333, S = 40;
  const auto t = test::make_uniform(size_t(n_rays) * S, 0.f, 1.f, 1);
  const auto gx = test::make_uniform(3 * t.size(), -1.f, 1.f, 2);
  auto bt = cl::Buffer::from(rt, t), bgx = cl::Buffer::from(rt, gx);
  cl::Buffer go(rt, size_t(n_rays) * 12), gd(rt, size_t(n_rays) * 12);
  render::RayGradReducer red(rt);
  red.reduce(bt, bgx, n_rays, S, go, gd).wait();
  std::vector<float> ro, rd;
  test::ref_raygrad<float>(n_rays, S, t, gx, ro, rd);
  const auto dev_o = go.read_vec<float>(3 * size_t(n_rays));
  const auto dev_d = gd.read_vec<float>(3 * size_t(n_rays));
  CHECK(test::max_abs_err(dev_o, ro) < 1e-5);
  CHECK(test::max_abs_err(dev_d, rd) < 1e-5);
  red.reduce(bt, bgx, n_rays, S, go, gd).wait();
  CHECK(go.read_vec<float>(3 * size_t(n_rays)) == dev_o);  // deterministic
}

TEST_CASE("Ray gradient reduction over compact rows equals the reference, with the box clamp",
          "[render][raygrad]") {
  auto& rt = test::runtime();
  const int n_rays = 257, M = 24;
  const float bound = 1.0f;
  const auto t = test::make_uniform(size_t(n_rays) * M, 0.f, 2.f, 11);
  const auto o = test::make_uniform(3 * size_t(n_rays), -0.8f, 0.8f, 12);
  const auto d = test::make_uniform(3 * size_t(n_rays), -1.f, 1.f, 13);
  std::vector<int> offset(size_t(n_rays) + 1, 0);
  for (int r = 0; r < n_rays; ++r) offset[size_t(r) + 1] = offset[size_t(r)] + (r * 7) % (M + 1);
  const auto gx = test::make_uniform(3 * size_t(offset.back()) + 3, -1.f, 1.f, 14);
  auto bt = cl::Buffer::from(rt, t), bo = cl::Buffer::from(rt, o), bd = cl::Buffer::from(rt, d);
  auto bgx = cl::Buffer::from(rt, gx), boff = cl::Buffer::from(rt, offset);
  cl::Buffer go(rt, size_t(n_rays) * 12), gd(rt, size_t(n_rays) * 12);
  render::RayGradReducer red(rt);
  red.reduce_rows(&boff, bt, bo, bd, bgx, n_rays, M, bound, go, gd).wait();
  std::vector<float> ro, rd;
  test::ref_raygrad_rows<float>(n_rays, M, bound, offset, t, o, d, gx, ro, rd);
  CHECK(test::max_abs_err(go.read_vec<float>(3 * size_t(n_rays)), ro) < 1e-5);
  CHECK(test::max_abs_err(gd.read_vec<float>(3 * size_t(n_rays)), rd) < 1e-5);
  // Some components were clamped away: the unmasked sum differs.
  std::vector<float> uo, ud;
  test::ref_raygrad_rows<float>(n_rays, M, 1e9f, offset, t, o, d, gx, uo, ud);
  CHECK(test::max_abs_err(uo, ro) > 1e-2);
  // Full layout (no offset table) equals the plain reduction inside the box.
  const auto gfull = test::make_uniform(3 * size_t(n_rays) * M, -1.f, 1.f, 15);
  auto bgf = cl::Buffer::from(rt, gfull);
  red.reduce_rows(nullptr, bt, bo, bd, bgf, n_rays, M, 1e9f, go, gd).wait();
  std::vector<float> po, pd;
  test::ref_raygrad<float>(n_rays, M, t, gfull, po, pd);
  CHECK(test::max_abs_err(go.read_vec<float>(3 * size_t(n_rays)), po) < 1e-4);
  CHECK(test::max_abs_err(gd.read_vec<float>(3 * size_t(n_rays)), pd) < 1e-4);
}

namespace {
// A smooth synthetic field: h0, return logit and intensity logit of x, with gradients.
template <typename T>
void field(const T* x, T& h0, T& hp, T& hi, T* dh0, T* dhp, T* dhi) {
  h0 = T(1.5) * std::sin(T(3) * x[0]) + std::cos(T(2) * x[1]) + T(0.5) * x[2] + T(2);
  hp = T(2) * x[0] - x[2];
  hi = std::sin(T(2) * x[1] + x[2]);
  if (!dh0) return;
  dh0[0] = T(4.5) * std::cos(T(3) * x[0]);
  dh0[1] = T(-2) * std::sin(T(2) * x[1]);
  dh0[2] = T(0.5);
  dhp[0] = 2, dhp[1] = 0, dhp[2] = -1;
  const T c = std::cos(T(2) * x[1] + x[2]);
  dhi[0] = 0, dhi[1] = 2 * c, dhi[2] = c;
}
}  // namespace

TEST_CASE("Ray origin and direction gradients match finite differences of the rendering",
          "[render][raygrad]") {
  auto& rt = test::runtime();
  const float scale = 0.0125f;
  render::RenderConfig cfg;
  cfg.n_samples = 30;
  const int n_rays = 6, S = 30;
  render::RaySampler sampler(rt, cfg, scale);
  render::VolumeRenderer vr(rt, cfg, scale);
  render::RayGradReducer red(rt);
  std::vector<float> o, d;
  test::make_rays(n_rays, 5, o, d);
  const auto g = test::make_uniform(3 * size_t(n_rays), -1.f, 1.f, 6);
  const size_t n = size_t(n_rays) * S;

  // Device chain: sample, evaluate the field on the host, render, backward, reduce.
  auto bo = cl::Buffer::from(rt, o), bd = cl::Buffer::from(rt, d), bg = cl::Buffer::from(rt, g);
  cl::Buffer bt(rt, n * 4), bx(rt, n * 12);
  sampler.uniform(bo, bd, n_rays, true, 42, 0, bt, bx).wait();
  const auto t = bt.read_vec<float>(n);
  const auto x = bx.read_vec<float>(3 * n);
  std::vector<float> h0(n), head(2 * n), dh0(3 * n), dhp(3 * n), dhi(3 * n);
  for (size_t s = 0; s < n; ++s)
    field<float>(&x[3 * s], h0[s], head[2 * s], head[2 * s + 1], &dh0[3 * s], &dhp[3 * s],
                 &dhi[3 * s]);
  auto bh = cl::Buffer::from(rt, h0), bhead = cl::Buffer::from(rt, head);
  cl::Buffer out(rt, size_t(n_rays) * 12), w(rt, n * 4), gh0(rt, n * 4), ghead(rt, n * 8);
  vr.forward(bt, bh, bhead, n_rays, S, out, w);
  vr.backward(bt, bh, bhead, w, bg, n_rays, S, gh0, ghead);
  const auto g_h0 = gh0.read_vec<float>(n);
  const auto g_head = ghead.read_vec<float>(2 * n);
  std::vector<float> gx(3 * n);  // the field's input gradient (the hash grid's job in training)
  for (size_t s = 0; s < n; ++s)
    for (int c = 0; c < 3; ++c)
      gx[3 * s + c] = g_h0[s] * dh0[3 * s + c] + g_head[2 * s] * dhp[3 * s + c] +
                      g_head[2 * s + 1] * dhi[3 * s + c];
  auto bgx = cl::Buffer::from(rt, gx);
  cl::Buffer go(rt, size_t(n_rays) * 12), gd(rt, size_t(n_rays) * 12);
  red.reduce(bt, bgx, n_rays, S, go, gd).wait();
  const auto dev_o = go.read_vec<float>(3 * size_t(n_rays));
  const auto dev_d = gd.read_vec<float>(3 * size_t(n_rays));

  // Finite differences of L(o, d) = g · render(field(o + t d)) in double, t held fixed.
  std::vector<double> od(o.begin(), o.end()), dd(d.begin(), d.end());
  const std::vector<double> td(t.begin(), t.end());
  auto loss = [&]() {
    std::vector<double> hh(n), hd(2 * n), out_d, w_d;
    for (size_t s = 0; s < n; ++s) {
      const size_t r = s / S;
      const double xs[3] = {od[3 * r] + td[s] * dd[3 * r], od[3 * r + 1] + td[s] * dd[3 * r + 1],
                            od[3 * r + 2] + td[s] * dd[3 * r + 2]};
      field<double>(xs, hh[s], hd[2 * s], hd[2 * s + 1], nullptr, nullptr, nullptr);
    }
    test::ref_volume_fwd<double>(n_rays, S, vr.last_delta(), td, hh, hd, out_d, w_d);
    double l = 0;
    for (size_t i = 0; i < out_d.size(); ++i) l += g[i] * out_d[i];
    return l;
  };
  auto fd = [&](std::vector<double>& v, size_t i) {
    const double eps = 1e-6, keep = v[i];
    v[i] = keep + eps;
    const double lp = loss();
    v[i] = keep - eps;
    const double lm = loss();
    v[i] = keep;
    return float((lp - lm) / (2 * eps));
  };
  std::vector<float> fd_o(3 * n_rays), fd_d(3 * n_rays);
  for (int i = 0; i < 3 * n_rays; ++i) {
    fd_o[i] = fd(od, i);
    fd_d[i] = fd(dd, i);
  }
  INFO("dL/do[0] device " << dev_o[0] << " fd " << fd_o[0]);
  CHECK(test::max_sym_rel_err(dev_o, fd_o, 1e-5) < 2e-3);
  CHECK(test::max_sym_rel_err(dev_d, fd_d, 1e-5) < 2e-3);
}
