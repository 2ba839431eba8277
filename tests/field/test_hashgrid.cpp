// Hash-grid encoding: device vs host reference (forward, both parameter backwards, d_x), and
// finite-difference checks of the parameter gradient and of d_x on the device forward.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/rng.hpp"
#include "fd_4d.hpp"
#include "field/hash_grid.hpp"
#include "reference.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {
// 4 levels (res 5, 9, 17, 33; table 4096): two dense levels and two hashed ones.
field::HashGridConfig small_config() {
  field::HashGridConfig c;
  c.levels = 4;
  c.features = 2;
  c.log2_table_size = 12;
  c.base_resolution = 4.0f;
  c.per_level_scale = 2.0f;
  return c;
}
using test::uniform;
double dot(const std::vector<float>& a, const std::vector<float>& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += double(a[i]) * b[i];
  return s;
}
}  // namespace

TEST_CASE("hash grid level table", "[field][hashgrid]") {
  const auto lv = field::hash_grid_levels(small_config());
  REQUIRE(lv.size() == 4);
  CHECK(lv[0].res == 5);
  CHECK(lv[0].hashed == 0);
  CHECK(lv[1].hashed == 0);
  CHECK(lv[2].hashed == 1);
  CHECK(lv[3].size == 4096);
  CHECK(lv[1].offset == lv[0].size);
  const auto w = field::barf_level_weights(0.4, 4);  // a = 2
  CHECK(w[0] == 1.0f);
  CHECK(w[1] == 1.0f);
  CHECK(w[2] == 0.0f);
  CHECK(field::barf_level_weights(0.3, 4)[1] == Approx(0.5));
  field::HashGridConfig bad = small_config();
  bad.features = 3;
  CHECK_THROWS_AS(bad.validate(), ConfigError);
  bad = small_config();
  bad.schedule = "fast";
  CHECK_THROWS_AS(bad.validate(), ConfigError);
}

TEST_CASE("hash grid forward and backward match the host reference", "[field][hashgrid]") {
  auto& rt = test::runtime();
  for (int variant = 0; variant < 4; ++variant) {
    auto cfg = small_config();
    cfg.deterministic = variant % 2 == 0;
    cfg.schedule = variant < 2 ? "chunked" : "per_point";
    INFO("deterministic " << cfg.deterministic << ", schedule " << cfg.schedule);
    field::HashGrid grid(rt, cfg);
    const int n = 3000, lf = grid.n_output();
    const size_t off = 32;  // the module slice sits at an offset in the flat buffer
    std::vector<float> params(off + grid.n_params(), 0.0f);
    grid.init_params(params, off, 7);
    for (float p : std::vector<float>(params.begin() + off, params.end()))
      REQUIRE(std::fabs(p) <= 1e-4f);
    const auto table = uniform(grid.n_params(), -1.0f, 1.0f, 11);
    std::copy(table.begin(), table.end(), params.begin() + off);
    // A margin outside the unit box covers the clamped dense index and wrapped hashes.
    const auto x = uniform(size_t(n) * 3, -1.1f, 1.1f, 12);
    const auto d_enc = uniform(size_t(n) * lf, -1.0f, 1.0f, 13);
    const std::vector<float> weights = {1.0f, 0.75f, 0.25f, 0.0f};
    grid.set_level_weights(weights);

    auto b_params = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, x);
    auto b_denc = cl::Buffer::from(rt, d_enc);
    cl::Buffer b_enc(rt, size_t(n) * lf * 4), b_dx(rt, size_t(n) * 12);
    auto b_grad = cl::Buffer::from(rt, std::vector<float>(params.size(), 3.0f));  // stale values
    grid.forward(b_params, off, b_x, n, b_enc);
    grid.backward(b_params, off, b_x, n, b_denc, b_grad, off, &b_dx);

    const auto enc = b_enc.read_vec<float>(size_t(n) * lf);
    const auto grad = b_grad.read_vec<float>(params.size());
    const auto dx = b_dx.read_vec<float>(size_t(n) * 3);
    // Values are O(1) sums of 8 products: float rounding leaves ~1e-7 absolute error, so
    // the relative error is taken against a floor of 1e-2.
    const auto enc_ref = test::ref::hashgrid_fwd(cfg, table, x, weights);
    INFO("fwd abs err " << test::max_abs_err(enc, enc_ref));
    CHECK(test::max_sym_rel_err(enc, enc_ref, 1e-2) < 1e-5);
    const auto g_ref = test::ref::hashgrid_bwd(cfg, grid.n_params(), x, weights, d_enc);
    const std::vector<float> g_dev(grad.begin() + off, grad.end());
    INFO("grad abs err " << test::max_abs_err(g_dev, g_ref));
    // Coarse entries sum ~200 O(1) contributions in float: floor 1, bound ~√K·ε·|sum|.
    CHECK(test::max_sym_rel_err(g_dev, g_ref, 1.0) < 1e-5);
    CHECK(grad[off - 1] == 3.0f);  // outside the slice: untouched
    const auto dx_ref = test::ref::hashgrid_bwd_dx(cfg, table, x, weights, d_enc);
    INFO("dx abs err " << test::max_abs_err(dx, dx_ref));
    CHECK(test::max_sym_rel_err(dx, dx_ref, 1e-1) < 1e-5);
  }
}

TEST_CASE("hash grid gradients agree with finite differences of the device forward",
          "[field][hashgrid][fd]") {
  auto& rt = test::runtime();
  const auto cfg = small_config();
  field::HashGrid grid(rt, cfg);
  const auto levels = field::hash_grid_levels(cfg);
  const int n = 64, lf = grid.n_output();
  const auto params = uniform(grid.n_params(), -1.0f, 1.0f, 21);
  const auto r = uniform(size_t(n) * lf, -1.0f, 1.0f, 23);  // L = Σ r · enc
  const float h = 1e-3f;
  const auto x = test::fd_points(levels, n, h, 22);  // L is smooth around them
  grid.set_level_weights({1.0f, 0.5f, 1.0f, 0.8f});
  auto b_params = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, x);
  auto b_r = cl::Buffer::from(rt, r);
  cl::Buffer b_enc(rt, size_t(n) * lf * 4), b_grad(rt, params.size() * 4), b_dx(rt, size_t(n) * 12);
  grid.backward(b_params, 0, b_x, n, b_r, b_grad, 0, &b_dx);
  const auto grad = b_grad.read_vec<float>(params.size());
  const auto dx = b_dx.read_vec<float>(size_t(n) * 3);
  auto loss = [&](const std::vector<float>& p, const std::vector<float>& xs) {
    b_params.write_vec(p);
    b_x.write_vec(xs);
    grid.forward(b_params, 0, b_x, n, b_enc);
    return dot(b_enc.read_vec<float>(size_t(n) * lf), r);
  };
  SECTION("parameters") {
    // L is linear in the table: central differences are exact up to rounding.
    std::vector<float> fd, an;
    for (size_t k = 0; k < grad.size() && fd.size() < 40; k += 97) {
      if (grad[k] == 0.0f) continue;
      auto p = params;
      p[k] += 0.5f;
      const double lp = loss(p, x);
      p[k] -= 1.0f;
      fd.push_back(float((lp - loss(p, x)) / 1.0));
      an.push_back(grad[k]);
    }
    REQUIRE(fd.size() >= 20);
    CHECK(test::max_sym_rel_err(fd, an, 1e-3) < 1e-3);
  }
  SECTION("positions") {
    std::vector<float> fd, an;
    for (size_t k = 0; k < x.size(); ++k) {
      auto xp = x, xm = x;
      xp[k] += h;
      xm[k] -= h;
      fd.push_back(float((loss(params, xp) - loss(params, xm)) / (2.0 * h)));
      an.push_back(dx[k]);
    }
    CHECK(test::max_sym_rel_err(fd, an, 1e-1) < 1e-2);
  }
}

TEST_CASE("hash grid fp16 table: forward and d_x on fp16-exact tables match the reference",
          "[field][hashgrid][half]") {
  auto& rt = test::runtime();
  for (const char* schedule : {"chunked", "per_point"}) {
    auto cfg = small_config();
    cfg.half_table = true;
    cfg.schedule = schedule;
    INFO("schedule " << schedule);
    field::HashGrid grid(rt, cfg);
    const int n = 2000, lf = grid.n_output();
    const auto x = uniform(size_t(n) * 3, -1.0f, 1.0f, 31);
    const auto d_enc = uniform(size_t(n) * lf, -1.0f, 1.0f, 32);
    const std::vector<float> weights(4, 1.0f);
    auto b_x = cl::Buffer::from(rt, x), b_denc = cl::Buffer::from(rt, d_enc);
    cl::Buffer b_enc(rt, size_t(n) * lf * 4), b_dx(rt, size_t(n) * 12),
        b_grad(rt, grid.n_params() * 4), b_params(rt, grid.n_params() * 4);
    for (uint64_t seed : {33u, 34u}) {  // second round: parameters changed on the device
      // k / 1024 with |k| ≤ 1024 has at most 11 significant bits: exact in fp16.
      Rng r(seed);
      std::vector<float> table(grid.n_params());
      for (auto& v : table) v = float(int(r.below(2049)) - 1024) / 1024.0f;
      b_params.write_vec(table);
      grid.params_changed();
      grid.forward(b_params, 0, b_x, n, b_enc);
      grid.backward(b_params, 0, b_x, n, b_denc, b_grad, 0, &b_dx);
      const auto enc_ref = test::ref::hashgrid_fwd(cfg, table, x, weights);
      const auto dx_ref = test::ref::hashgrid_bwd_dx(cfg, table, x, weights, d_enc);
      CHECK(test::max_sym_rel_err(b_enc.read_vec<float>(size_t(n) * lf), enc_ref, 1e-2) < 1e-5);
      // d_x sums terms up to scale·|table| ≈ 30 with cancellation: floor 1.
      CHECK(test::max_sym_rel_err(b_dx.read_vec<float>(size_t(n) * 3), dx_ref, 1.0) < 1e-5);
    }
    // A general table is rounded to the nearest fp16: relative error ≤ 2^-11 per entry.
    const auto table = uniform(grid.n_params(), 0.5f, 1.0f, 35);
    b_params.write_vec(table);
    grid.params_changed();
    grid.forward(b_params, 0, b_x, n, b_enc);
    CHECK(test::max_sym_rel_err(b_enc.read_vec<float>(size_t(n) * lf),
                                test::ref::hashgrid_fwd(cfg, table, x, weights)) < 1.0 / 2048);
  }
}
