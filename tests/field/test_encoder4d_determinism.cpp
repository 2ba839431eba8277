// Determinism of LiDAR4D's 4D encodings: a few training steps of planes (both groups at the
// point's time, plus the dynamic group at a shifted neighbour position and time accumulated
// into the same gradient, as LiDAR4D's flow blending does), the static 3D hash grid and the
// time-sliced hash grids, Adam over one flat buffer, give bit-identical parameters and
// position gradients from one seed, and different ones from another seed.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>

#include "core/rng.hpp"
#include "field/adam.hpp"
#include "field/hash_grid.hpp"
#include "field/kplanes.hpp"
#include "field/param_layout.hpp"
#include "field/time_hash_grid.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using field::PlaneGroups;

namespace {
struct Result {
  std::vector<float> params, dx_planes, dx_neighbour, dx_static, dx_time;
  double first_loss = 0, last_loss = 0;
};

Result train(uint64_t seed, int steps) {
  auto& rt = test::runtime();
  field::KPlanesConfig pc;
  pc.resolution = 8;
  pc.scales = 2;
  pc.features = 4;
  field::HashGridConfig hc = field::lidar4d_static_hash_config();
  hc.log2_table_size = 12;
  hc.base_resolution = 8.0f;
  hc.per_level_scale = 1.5f;
  field::TimeHashGridConfig tc;
  tc.base_resolution = 8.0f;
  tc.per_level_scale = 1.5f;
  tc.log2_table_xy = 10;
  tc.log2_table_xz = 9;
  tc.log2_table_yz = 9;
  field::KPlanes planes(rt, pc);
  field::HashGrid stat(rt, hc);
  field::TimeHashGrid dyn(rt, tc);
  field::ParamLayout layout;
  const auto s_p = layout.add("planes", planes.n_params());
  const auto s_s = layout.add("hash_static", stat.n_params());
  const auto s_d = layout.add("hash_dynamic", dyn.n_params());
  std::vector<float> host(layout.total(), 0.0f);
  planes.init_params(host, s_p.offset, seed);
  stat.init_params(host, s_s.offset, seed + 1);
  // Larger than the ±1e-4 default so that the product of three planes trains in a few steps.
  Rng init(seed + 2);
  for (size_t i = 0; i < s_d.count; ++i) host[s_d.offset + i] = init.uniform(0.5f, 1.0f);

  const int n = 4096;
  Rng rng(seed + 3);
  const size_t count = size_t(n);
  std::vector<float> x(count * 3), xn(count * 3), t(count), tn(count), target(count);
  for (int i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      x[size_t(i) * 3 + a] = rng.uniform(-1.0f, 1.0f);
      xn[size_t(i) * 3 + a] = x[size_t(i) * 3 + a] + rng.uniform(-0.05f, 0.05f);  // "flow"
    }
    t[size_t(i)] = float(i % 5) / 4.0f;
    tn[size_t(i)] = std::min(1.0f, t[size_t(i)] + 0.25f);
    target[size_t(i)] = rng.uniform(0.0f, 1.0f);
  }
  const int wp = planes.n_output(), wn = planes.n_output(PlaneGroups::Dynamic);
  const int ws = stat.n_output(), wd = dyn.n_output();
  auto b_params = cl::Buffer::from(rt, host);
  cl::Buffer b_grad(rt, host.size() * 4);
  b_grad.fill_zero();
  auto b_x = cl::Buffer::from(rt, x), b_xn = cl::Buffer::from(rt, xn);
  auto b_t = cl::Buffer::from(rt, t), b_tn = cl::Buffer::from(rt, tn);
  cl::Buffer b_ep(rt, size_t(n) * wp * 4), b_en(rt, size_t(n) * wn * 4),
      b_es(rt, size_t(n) * ws * 4), b_ed(rt, size_t(n) * wd * 4), b_dxp(rt, size_t(n) * 12),
      b_dxn(rt, size_t(n) * 12), b_dxs(rt, size_t(n) * 12), b_dxd(rt, size_t(n) * 12);
  field::Adam adam(rt, layout.total());
  Result res;
  for (int step = 0; step < steps; ++step) {
    planes.forward(b_params, s_p.offset, b_x, b_t, n, b_ep);
    planes.forward(b_params, s_p.offset, b_xn, b_tn, n, b_en, PlaneGroups::Dynamic);
    stat.forward(b_params, s_s.offset, b_x, n, b_es);
    dyn.forward(b_params, s_d.offset, b_x, b_t, n, b_ed);
    // Loss 0.5 Σ_i (mean of the features − target_i)², the neighbour's features at weight 1/2.
    const auto ep = b_ep.read_vec<float>(size_t(n) * wp), en = b_en.read_vec<float>(size_t(n) * wn);
    const auto es = b_es.read_vec<float>(size_t(n) * ws), ed = b_ed.read_vec<float>(size_t(n) * wd);
    const double cols = wp + 0.5 * wn + ws + wd;
    std::vector<float> dp(ep.size()), dn(en.size()), ds(es.size()), dd(ed.size());
    double loss = 0;
    for (int i = 0; i < n; ++i) {
      double s = 0;
      for (int c = 0; c < wp; ++c) s += ep[size_t(i) * wp + c];
      for (int c = 0; c < wn; ++c) s += 0.5 * en[size_t(i) * wn + c];
      for (int c = 0; c < ws; ++c) s += es[size_t(i) * ws + c];
      for (int c = 0; c < wd; ++c) s += ed[size_t(i) * wd + c];
      const double r = s / cols - target[size_t(i)];
      loss += 0.5 * r * r;
      const float g = float(r / cols / n);
      for (int c = 0; c < wp; ++c) dp[size_t(i) * wp + c] = g;
      for (int c = 0; c < wn; ++c) dn[size_t(i) * wn + c] = 0.5f * g;
      for (int c = 0; c < ws; ++c) ds[size_t(i) * ws + c] = g;
      for (int c = 0; c < wd; ++c) dd[size_t(i) * wd + c] = g;
    }
    if (step == 0) res.first_loss = loss;
    res.last_loss = loss;
    b_ep.write_vec(dp);
    b_en.write_vec(dn);
    b_es.write_vec(ds);
    b_ed.write_vec(dd);
    planes.backward(b_params, s_p.offset, b_x, b_t, n, b_ep, b_grad, s_p.offset, &b_dxp);
    planes.backward(b_params, s_p.offset, b_xn, b_tn, n, b_en, b_grad, s_p.offset, &b_dxn,
                    PlaneGroups::Dynamic, true);
    stat.backward(b_params, s_s.offset, b_x, n, b_es, b_grad, s_s.offset, &b_dxs);
    dyn.backward(b_params, s_d.offset, b_x, b_t, n, b_ed, b_grad, s_d.offset, &b_dxd);
    adam.begin_step();
    adam.update(b_params, b_grad, 0, layout.total(), 1e-2f);
    rt.finish();
  }
  res.params = b_params.read_vec<float>(host.size());
  res.dx_planes = b_dxp.read_vec<float>(size_t(n) * 3);
  res.dx_neighbour = b_dxn.read_vec<float>(size_t(n) * 3);
  res.dx_static = b_dxs.read_vec<float>(size_t(n) * 3);
  res.dx_time = b_dxd.read_vec<float>(size_t(n) * 3);
  return res;
}

bool bit_identical(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}
}  // namespace

TEST_CASE("4D encoder training steps from one seed are bit-identical",
          "[field][kplanes][timehash][determinism]") {
  const auto a = train(42, 5);
  const auto b = train(42, 5);
  CHECK(a.last_loss < a.first_loss);  // the steps do train
  CHECK(bit_identical(a.params, b.params));
  CHECK(bit_identical(a.dx_planes, b.dx_planes));
  CHECK(bit_identical(a.dx_neighbour, b.dx_neighbour));
  CHECK(bit_identical(a.dx_static, b.dx_static));
  CHECK(bit_identical(a.dx_time, b.dx_time));
  const auto c = train(43, 5);
  CHECK_FALSE(bit_identical(a.params, c.params));  // the comparison can fail
}
