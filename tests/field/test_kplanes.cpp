// K-Planes 4D plane encoding: device vs host reference (forward, parameter backward, d_x; both
// groups and each alone, into a wider row, accumulate), finite differences of the device
// forward for the parameter and position gradients, and the config's refusals.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/config.hpp"
#include "core/rng.hpp"
#include "field/frame_time.hpp"
#include "field/kplanes.hpp"
#include "fd_4d.hpp"
#include "reference_4d.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using field::PlaneGroups;

namespace {
// 2 scales of 5 and 10 points, time 3, 2 features: 330 entries.
field::KPlanesConfig small_config() {
  field::KPlanesConfig c;
  c.resolution = 5;
  c.scales = 2;
  c.time_resolution = 3;
  c.features = 2;
  return c;
}
using test::uniform;
const char* name(PlaneGroups g) {
  return g == PlaneGroups::Both ? "both" : g == PlaneGroups::Static ? "static" : "dynamic";
}
}  // namespace

TEST_CASE("kplanes layout, init and config refusals", "[field][kplanes]") {
  const auto cfg = small_config();
  const auto planes = field::kplanes_layout(cfg);
  REQUIRE(planes.size() == 12);
  CHECK(planes[0].width == 5);    // xy at scale 0
  CHECK(planes[3].height == 3);   // xt: time axis
  CHECK(planes[6].width == 10);   // xy at scale 1
  CHECK(planes[1].offset == 25);
  auto& rt = test::runtime();
  field::KPlanes kp(rt, cfg);
  CHECK(kp.n_params() == size_t(3 * 25 + 3 * 15 + 3 * 100 + 3 * 30) * 2);
  CHECK(kp.n_output() == 8);
  CHECK(kp.n_output(PlaneGroups::Dynamic) == 4);
  std::vector<float> p(kp.n_params() + 8, -7.0f);
  kp.init_params(p, 8, 3);
  CHECK(p[7] == -7.0f);
  for (const auto& pl : planes)
    for (size_t e = 0; e < size_t(pl.width) * pl.height * 2; ++e) {
      const float v = p[8 + size_t(pl.offset) * 2 + e];
      if (pl.plane >= 3) REQUIRE(v == 1.0f);
      else REQUIRE((v >= 0.1f && v <= 0.5f));
    }
  // The LiDAR4D defaults: 32·{1, 2, 4, 8}, time 8, 8 features: 64 columns.
  const field::KPlanesConfig def;
  CHECK(def.resolution * (1 << (def.scales - 1)) == 256);
  CHECK(field::kplanes_layout(def).back().width == 256);

  using Catch::Matchers::Contains;
  CHECK(field::KPlanesConfig::from_json(Json{{"scales", 2}, {"features", 4}}, "kp").features == 4);
  CHECK_THROWS_WITH(field::KPlanesConfig::from_json(Json{{"featurs", 4}}, "kp"),
                    Contains("featurs"));
  CHECK_THROWS_WITH(field::KPlanesConfig::from_json(Json{{"features", 3}}, "kp"),
                    Contains("'features'"));
  CHECK_THROWS_WITH(field::KPlanesConfig::from_json(Json{{"resolution", 1}}, "kp"),
                    Contains("'resolution'"));
  CHECK_THROWS_WITH(field::KPlanesConfig::from_json(Json{{"time_resolution", 1}}, "kp"),
                    Contains("'time_resolution'"));
  CHECK_THROWS_WITH(field::KPlanesConfig::from_json(Json{{"init_lo", 0.6}}, "kp"),
                    Contains("'init_lo'"));
  CHECK_THROWS_WITH(
      field::KPlanesConfig::from_json(Json{{"resolution", 2048}, {"scales", 4}}, "kp"),
      Contains("'resolution'"));
  CHECK_THROWS_AS(field::KPlanesConfig::from_json(Json{{"scales", "4"}}, "kp"), ConfigError);
  const auto round = field::KPlanesConfig::from_json(small_config().to_json(), "kp");
  CHECK(round.to_json() == small_config().to_json());
}

TEST_CASE("kplanes forward and backward match the host reference", "[field][kplanes]") {
  auto& rt = test::runtime();
  for (int chunk : {0, 1, 7})
    for (PlaneGroups groups : {PlaneGroups::Both, PlaneGroups::Static, PlaneGroups::Dynamic}) {
      auto cfg = small_config();
      cfg.chunk = chunk;
      INFO("chunk " << chunk << ", groups " << name(groups));
      field::KPlanes kp(rt, cfg);
      const int n = 2000, w = kp.n_output(groups), stride = w + 3, col = 2;
      const size_t off = 16;
      const auto table = uniform(kp.n_params(), -1.0f, 1.0f, 11);
      std::vector<float> params(off, 0.0f);
      params.insert(params.end(), table.begin(), table.end());
      // A margin outside the box and outside [0, 1] in time exercises the border clamp.
      const auto x = uniform(size_t(n) * 3, -1.1f, 1.1f, 12);
      const auto t = uniform(size_t(n), -0.1f, 1.1f, 14);
      const auto d_enc = uniform(size_t(n) * w, -1.0f, 1.0f, 13);
      std::vector<float> d_row(size_t(n) * stride, 9.0f);  // padding columns must not be read
      for (int i = 0; i < n; ++i)
        for (int c = 0; c < w; ++c) d_row[size_t(i) * stride + col + c] = d_enc[size_t(i) * w + c];

      auto b_params = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, x);
      auto b_t = cl::Buffer::from(rt, t), b_d = cl::Buffer::from(rt, d_row);
      auto b_enc = cl::Buffer::from(rt, std::vector<float>(size_t(n) * stride, 5.0f));
      auto b_grad = cl::Buffer::from(rt, std::vector<float>(params.size(), 3.0f));
      cl::Buffer b_dx(rt, size_t(n) * 12);
      kp.forward(b_params, off, b_x, b_t, n, b_enc, groups, stride, col);
      kp.backward(b_params, off, b_x, b_t, n, b_d, b_grad, off, &b_dx, groups, false, stride, col);

      const auto row = b_enc.read_vec<float>(size_t(n) * stride);
      std::vector<float> enc;
      for (int i = 0; i < n; ++i) {
        REQUIRE(row[size_t(i) * stride + 1] == 5.0f);  // outside the columns: untouched
        for (int c = 0; c < w; ++c) enc.push_back(row[size_t(i) * stride + col + c]);
      }
      const auto enc_ref = test::ref::kplanes_fwd(cfg, table, x, t, groups);
      INFO("fwd abs err " << test::max_abs_err(enc, enc_ref));
      CHECK(test::max_sym_rel_err(enc, enc_ref, 1e-2) < 1e-5);

      const auto grad = b_grad.read_vec<float>(params.size());
      auto g_ref = test::ref::kplanes_bwd(cfg, table, x, t, d_enc, groups);
      std::vector<float> g_dev(grad.begin() + off, grad.end());
      std::vector<char> active(g_dev.size(), 1);
      if (groups != PlaneGroups::Both)  // the other group's planes keep their (stale) values
        for (const auto& pl : kp.planes())
          if ((pl.plane >= 3) != (groups == PlaneGroups::Dynamic))
            for (size_t e = 0; e < size_t(pl.width) * pl.height * 2; ++e) {
              REQUIRE(g_dev[size_t(pl.offset) * 2 + e] == 3.0f);
              g_ref[size_t(pl.offset) * 2 + e] = 3.0f;
              active[size_t(pl.offset) * 2 + e] = 0;
            }
      INFO("grad abs err " << test::max_abs_err(g_dev, g_ref));
      CHECK(test::max_sym_rel_err(g_dev, g_ref, 1.0) < 2e-5);
      CHECK(grad[off - 1] == 3.0f);
      const auto dx_ref = test::ref::kplanes_bwd_dx(cfg, table, x, t, d_enc, groups);
      const auto dx = b_dx.read_vec<float>(size_t(n) * 3);
      INFO("dx abs err " << test::max_abs_err(dx, dx_ref));
      CHECK(test::max_sym_rel_err(dx, dx_ref, 1.0) < 1e-5);

      // accumulate adds a second pass onto the first.
      kp.backward(b_params, off, b_x, b_t, n, b_d, b_grad, off, nullptr, groups, true, stride, col);
      const auto grad2 = b_grad.read_vec<float>(params.size());
      std::vector<float> g2(grad2.begin() + off, grad2.end()), g2_ref = g_ref;
      for (size_t k = 0; k < g2_ref.size(); ++k)
        if (active[k]) g2_ref[k] = 2.0f * g_ref[k];
      CHECK(test::max_sym_rel_err(g2, g2_ref, 1.0) < 2e-5);
    }
}

TEST_CASE("kplanes gradients agree with finite differences of the device forward",
          "[field][kplanes][fd]") {
  auto& rt = test::runtime();
  const auto cfg = small_config();
  field::KPlanes kp(rt, cfg);
  const int n = 48, w = kp.n_output();
  auto params = uniform(kp.n_params(), 0.2f, 1.2f, 21);
  const auto r = uniform(size_t(n) * w, -1.0f, 1.0f, 23);  // L = Σ r · enc
  const auto t = uniform(size_t(n), 0.0f, 1.0f, 24);
  const float h = 1e-3f;
  // Points at least 4h·(R − 1)/2 from every cell face at every scale, so L is smooth in x.
  std::vector<float> x;
  Rng rng(22);
  while (x.size() < size_t(n) * 3) {
    float p[3];
    bool ok = true;
    for (float& v : p) {
      v = rng.uniform(-0.95f, 0.95f);
      for (int s = 0; s < cfg.scales; ++s) {
        const double span = double(cfg.resolution << s) - 1.0, pos = (v + 1.0) * 0.5 * span;
        const double fr = pos - std::floor(pos), m = 4 * h * 0.5 * span;
        ok = ok && fr > m && fr < 1 - m;
      }
    }
    if (ok) x.insert(x.end(), p, p + 3);
  }
  test::check_4d_gradients(rt, kp, params, x, t, r, w, h, 7);
}

TEST_CASE("kplanes launcher refuses bad shapes; frame times", "[field][kplanes]") {
  auto& rt = test::runtime();
  field::KPlanes kp(rt, small_config());
  const int n = 10;
  cl::Buffer b_p(rt, kp.n_params() * 4), b_x(rt, size_t(n) * 12), b_t(rt, size_t(n) * 4),
      b_enc(rt, size_t(n) * 8 * 4), b_small(rt, size_t(n) * 4 * 4), b_g(rt, kp.n_params() * 4);
  CHECK_NOTHROW(kp.forward(b_p, 0, b_x, b_t, n, b_enc));
  CHECK_THROWS_AS(kp.forward(b_p, 0, b_x, b_t, n, b_small), Error);           // 8 columns
  CHECK_NOTHROW(kp.forward(b_p, 0, b_x, b_t, n, b_small, PlaneGroups::Static));  // 4 columns
  CHECK_THROWS_AS(kp.forward(b_p, 0, b_x, b_t, n, b_enc, PlaneGroups::Both, 8, 1), Error);
  CHECK_THROWS_AS(kp.forward(b_p, 4, b_x, b_t, n, b_enc), Error);             // slice past end
  CHECK_THROWS_AS(kp.forward(b_p, 0, b_x, b_t, n + 1, b_enc), Error);
  CHECK_THROWS_AS(kp.backward(b_p, 0, b_x, b_t, n, b_enc, b_g, 1), Error);
  rt.finish();

  CHECK(field::frame_time(7, 7, 51) == 0.0f);
  CHECK(field::frame_time(57, 7, 51) == 1.0f);
  CHECK(field::frame_time(32, 7, 51) == Approx(0.5));
  CHECK(field::frame_time(3, 3, 1) == 0.0f);
  CHECK_THROWS_AS(field::frame_time(58, 7, 51), Error);
  CHECK_THROWS_AS(field::frame_time(6, 7, 51), Error);
}

TEST_CASE("kplanes at LiDAR4D's sizes (8 features, 32..256, time 8) match the reference",
          "[field][kplanes]") {
  auto& rt = test::runtime();
  const field::KPlanesConfig cfg;
  field::KPlanes kp(rt, cfg);
  const int n = 300, w = kp.n_output();
  REQUIRE(w == 64);
  const auto table = uniform(kp.n_params(), -1.0f, 1.0f, 61);
  const auto x = uniform(size_t(n) * 3, -1.0f, 1.0f, 62);
  const auto t = uniform(size_t(n), 0.0f, 1.0f, 63);
  const auto d_enc = uniform(size_t(n) * w, -1.0f, 1.0f, 64);
  auto b_p = cl::Buffer::from(rt, table), b_x = cl::Buffer::from(rt, x);
  auto b_t = cl::Buffer::from(rt, t), b_d = cl::Buffer::from(rt, d_enc);
  cl::Buffer b_enc(rt, size_t(n) * w * 4), b_g(rt, table.size() * 4), b_dx(rt, size_t(n) * 12);
  kp.forward(b_p, 0, b_x, b_t, n, b_enc);
  kp.backward(b_p, 0, b_x, b_t, n, b_d, b_g, 0, &b_dx);
  CHECK(test::max_sym_rel_err(b_enc.read_vec<float>(size_t(n) * w),
                              test::ref::kplanes_fwd(cfg, table, x, t, PlaneGroups::Both),
                              1e-2) < 1e-5);
  CHECK(test::max_sym_rel_err(b_g.read_vec<float>(table.size()),
                              test::ref::kplanes_bwd(cfg, table, x, t, d_enc, PlaneGroups::Both),
                              1e-1) < 1e-5);
  CHECK(test::max_sym_rel_err(b_dx.read_vec<float>(size_t(n) * 3),
                              test::ref::kplanes_bwd_dx(cfg, table, x, t, d_enc, PlaneGroups::Both),
                              1.0) < 3e-5);  // |d_x| up to ~100 (∂pos/∂x = 127.5): float sums
}
