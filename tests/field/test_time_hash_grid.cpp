// Time-sliced 2D hash grids: device vs host reference (forward, parameter backward, d_x; into a
// wider row, accumulate), finite differences of the device forward, the time blend at the
// slices, the config's refusals, and LiDAR4D's static 3D hash grid as a HashGrid config.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/config.hpp"
#include "core/rng.hpp"
#include "field/time_hash_grid.hpp"
#include "reference.hpp"
#include "fd_4d.hpp"
#include "reference_4d.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {
// 3 levels (res 6, 10, 18): xy table 2^7 (dense, dense, hashed), xz and yz 2^6 (dense, hashed,
// hashed); 4 time slices, 2 features.
field::TimeHashGridConfig small_config() {
  field::TimeHashGridConfig c;
  c.levels = 3;
  c.features = 2;
  c.base_resolution = 4.0f;
  c.per_level_scale = 2.0f;
  c.log2_table_xy = 7;
  c.log2_table_xz = 6;
  c.log2_table_yz = 6;
  c.time_slices = 4;
  return c;
}
using test::uniform;
}  // namespace

TEST_CASE("time hash grid tables and config refusals", "[field][timehash]") {
  const auto planes = field::time_hash_grid_planes(small_config());
  REQUIRE(planes.size() == 3);
  CHECK(planes[0].levels[0].res == 5);
  CHECK(planes[0].levels[1].hashed == 0);
  CHECK(planes[0].levels[2].hashed == 1);
  CHECK(planes[1].levels[1].hashed == 1);
  CHECK(planes[1].offset == planes[0].slice_entries * 4);
  // LiDAR4D's sizes: every level of a 512-based 2D grid is hashed; finest scale 32768 − 1.
  const field::TimeHashGridConfig def;
  const auto dp = field::time_hash_grid_planes(def);
  CHECK(dp[0].slice_entries == 8u << 14);
  CHECK(dp[2].slice_entries == 8u << 12);
  CHECK(dp[0].levels.back().scale == Approx(32767.0).epsilon(1e-5));

  using Catch::Matchers::Contains;
  CHECK(field::TimeHashGridConfig::from_json(Json{{"time_slices", 25}}, "th").time_slices == 25);
  CHECK_THROWS_WITH(field::TimeHashGridConfig::from_json(Json{{"slices", 4}}, "th"),
                    Contains("slices"));
  CHECK_THROWS_WITH(field::TimeHashGridConfig::from_json(Json{{"features", 6}}, "th"),
                    Contains("'features'"));
  CHECK_THROWS_WITH(field::TimeHashGridConfig::from_json(Json{{"time_slices", 0}}, "th"),
                    Contains("'time_slices'"));
  CHECK_THROWS_WITH(field::TimeHashGridConfig::from_json(Json{{"log2_table_xz", 30}}, "th"),
                    Contains("'log2_table_xz'"));
  CHECK_THROWS_WITH(field::TimeHashGridConfig::from_json(Json{{"per_level_scale", 4.0}}, "th"),
                    Contains("finest resolution"));
  const auto round = field::TimeHashGridConfig::from_json(small_config().to_json(), "th");
  CHECK(round.to_json() == small_config().to_json());
}

TEST_CASE("time hash grid forward and backward match the host reference", "[field][timehash]") {
  auto& rt = test::runtime();
  for (int variant = 0; variant < 4; ++variant) {
    auto cfg = small_config();
    cfg.chunk = variant == 1 ? 1 : variant == 2 ? 5 : 0;
    if (variant == 3) cfg.time_slices = 1;  // a static stack: every time reads slice 0
    INFO("chunk " << cfg.chunk << ", slices " << cfg.time_slices);
    field::TimeHashGrid grid(rt, cfg);
    const int n = 2000, w = grid.n_output(), stride = w + 2, col = 1;
    const size_t off = 32;
    const auto table = uniform(grid.n_params(), -1.0f, 1.0f, 11);
    std::vector<float> params(off, 0.0f);
    params.insert(params.end(), table.begin(), table.end());
    const auto x = uniform(size_t(n) * 3, -1.1f, 1.1f, 12);
    auto t = uniform(size_t(n), -0.1f, 1.1f, 14);
    t[0] = 0.0f;  // exactly on slices, and the last one
    t[1] = 1.0f / 3.0f;
    t[2] = 1.0f;
    const auto d_enc = uniform(size_t(n) * w, -1.0f, 1.0f, 13);
    std::vector<float> d_row(size_t(n) * stride, 9.0f);
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < w; ++c) d_row[size_t(i) * stride + col + c] = d_enc[size_t(i) * w + c];

    auto b_params = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, x);
    auto b_t = cl::Buffer::from(rt, t), b_d = cl::Buffer::from(rt, d_row);
    auto b_enc = cl::Buffer::from(rt, std::vector<float>(size_t(n) * stride, 5.0f));
    auto b_grad = cl::Buffer::from(rt, std::vector<float>(params.size(), 3.0f));
    cl::Buffer b_dx(rt, size_t(n) * 12);
    grid.forward(b_params, off, b_x, b_t, n, b_enc, stride, col);
    grid.backward(b_params, off, b_x, b_t, n, b_d, b_grad, off, &b_dx, false, stride, col);

    const auto row = b_enc.read_vec<float>(size_t(n) * stride);
    std::vector<float> enc;
    for (int i = 0; i < n; ++i) {
      REQUIRE(row[size_t(i) * stride] == 5.0f);
      for (int c = 0; c < w; ++c) enc.push_back(row[size_t(i) * stride + col + c]);
    }
    const auto enc_ref = test::ref::time_hash_fwd(cfg, table, x, t);
    INFO("fwd abs err " << test::max_abs_err(enc, enc_ref));
    CHECK(test::max_sym_rel_err(enc, enc_ref, 1e-2) < 1e-5);
    const auto grad = b_grad.read_vec<float>(params.size());
    const std::vector<float> g_dev(grad.begin() + off, grad.end());
    const auto g_ref = test::ref::time_hash_bwd(cfg, table, x, t, d_enc);
    INFO("grad abs err " << test::max_abs_err(g_dev, g_ref));
    CHECK(test::max_sym_rel_err(g_dev, g_ref, 1.0) < 2e-5);
    CHECK(grad[off - 1] == 3.0f);
    const auto dx_ref = test::ref::time_hash_bwd_dx(cfg, table, x, t, d_enc);
    const auto dx = b_dx.read_vec<float>(size_t(n) * 3);
    INFO("dx abs err " << test::max_abs_err(dx, dx_ref));
    CHECK(test::max_sym_rel_err(dx, dx_ref, 1.0) < 1e-5);

    grid.backward(b_params, off, b_x, b_t, n, b_d, b_grad, off, nullptr, true, stride, col);
    const auto grad2 = b_grad.read_vec<float>(params.size());
    std::vector<float> g2(grad2.begin() + off, grad2.end()), g2_ref(g_ref.size());
    for (size_t k = 0; k < g_ref.size(); ++k) g2_ref[k] = 2.0f * g_ref[k];
    CHECK(test::max_sym_rel_err(g2, g2_ref, 1.0) < 2e-5);
  }
}

TEST_CASE("time hash grid: a time on a slice reads that slice alone", "[field][timehash]") {
  auto& rt = test::runtime();
  const auto cfg = small_config();
  field::TimeHashGrid grid(rt, cfg);
  const int n = 64, w = grid.n_output();
  const auto x = uniform(size_t(n) * 3, -1.0f, 1.0f, 41);
  auto table = uniform(grid.n_params(), -1.0f, 1.0f, 42);
  auto b_p = cl::Buffer::from(rt, table), b_x = cl::Buffer::from(rt, x);
  cl::Buffer b_enc(rt, size_t(n) * w * 4);
  auto enc_at = [&](float time) {
    auto b_t = cl::Buffer::from(rt, std::vector<float>(size_t(n), time));
    grid.forward(b_p, 0, b_x, b_t, n, b_enc);
    return b_enc.read_vec<float>(size_t(n) * w);
  };
  // T = 4: t = 1/3 lies on slice 1 (weight 1), t = 1/2 between slices 1 and 2, t = 1 on slice 3.
  const auto at0 = enc_at(0.0f), at1 = enc_at(1.0f / 3.0f), mid = enc_at(0.5f), at3 = enc_at(1.0f);
  for (const auto& pl : grid.planes())  // change slice 2 of every plane
    for (size_t e = 0; e < size_t(pl.slice_entries) * 2; ++e)
      table[(size_t(pl.offset) + 2 * size_t(pl.slice_entries)) * 2 + e] += 0.5f;
  b_p.write_vec(table);
  // t = 0 and t = 1 give u = 0 and 3 and w1 = 0 exactly on any device (also when u − s0 is
  // contracted into an FMA): bit equality.
  CHECK(enc_at(0.0f) == at0);
  CHECK(enc_at(1.0f) == at3);
  CHECK(enc_at(-0.5f) == at0);  // times outside [0, 1] are clamped
  CHECK(enc_at(1.5f) == at3);
  // t = float(1/3): u = 3t rounds to 1, so w1 = 0 here; a device that fuses u − s0 into
  // fma(t, 3, −1) gets w1 = 3e-8, and slice 2's +0.5 moves the encoding by ~1.5e-8. Reading
  // slice 2 with any real weight (≥ 2e-6) moves it by more than the tolerance (absolute below 1).
  CHECK(test::sym_rel_err(enc_at(1.0f / 3.0f), at1, 1.0) <= 1e-6);
  CHECK(enc_at(0.5f) != mid);
}

TEST_CASE("time hash grid gradients agree with finite differences of the device forward",
          "[field][timehash][fd]") {
  auto& rt = test::runtime();
  const auto cfg = small_config();
  field::TimeHashGrid grid(rt, cfg);
  const auto& levels = grid.planes()[0].levels;
  const int n = 48, w = grid.n_output();
  const auto params = uniform(grid.n_params(), 0.2f, 1.2f, 21);
  const auto r = uniform(size_t(n) * w, -1.0f, 1.0f, 23);
  const auto t = uniform(size_t(n), 0.0f, 1.0f, 24);
  const float h = 1e-3f;
  const auto x = test::fd_points(levels, n, h, 22);
  test::check_4d_gradients(rt, grid, params, x, t, r, w, h, 5);
}

namespace {
// The grid at one time for every point (forward_at / backward_at) behind the launchers'
// (params, offset, x, t, n, ...) signature that check_4d_gradients calls; t is not read.
struct AtTime {
  field::TimeHashGrid& grid;
  float t;
  void forward(const cl::Buffer& p, size_t off, const cl::Buffer& x, const cl::Buffer&, int n,
               cl::Buffer& enc) {
    grid.forward_at(p, off, x, t, n, enc);
  }
  void backward(const cl::Buffer& p, size_t off, const cl::Buffer& x, const cl::Buffer&, int n,
                const cl::Buffer& d, cl::Buffer& g, size_t goff, cl::Buffer* dx) {
    grid.backward_at(p, off, x, t, n, d, g, goff, dx);
  }
};
}  // namespace

TEST_CASE("time hash grid at one time for all points matches the host reference",
          "[field][timehash]") {
  auto& rt = test::runtime();
  for (int variant = 0; variant < 3; ++variant) {
    auto cfg = small_config();
    cfg.chunk = variant == 1 ? 1 : 0;
    if (variant == 2) cfg.time_slices = 1;
    field::TimeHashGrid grid(rt, cfg);
    const int n = 1500, w = grid.n_output(), stride = w + 3, col = 2;
    const size_t off = 16;
    const auto table = uniform(grid.n_params(), -1.0f, 1.0f, 51);
    std::vector<float> params(off, 0.0f);
    params.insert(params.end(), table.begin(), table.end());
    const auto x = uniform(size_t(n) * 3, -1.1f, 1.1f, 52);
    const auto d_enc = uniform(size_t(n) * w, -1.0f, 1.0f, 53);
    std::vector<float> d_row(size_t(n) * stride, 9.0f);
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < w; ++c) d_row[size_t(i) * stride + col + c] = d_enc[size_t(i) * w + c];
    auto b_params = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, x);
    auto b_d = cl::Buffer::from(rt, d_row);
    // On a slice, between slices, the last slice, and clamped from outside [0, 1].
    for (const float time : {0.0f, 1.0f / 3.0f, 0.55f, 1.0f, -0.2f, 1.3f}) {
      INFO("variant " << variant << ", t = " << time);
      const std::vector<float> t(size_t(n), time);
      auto b_enc = cl::Buffer::from(rt, std::vector<float>(size_t(n) * stride, 5.0f));
      auto b_grad = cl::Buffer::from(rt, std::vector<float>(params.size(), 3.0f));
      cl::Buffer b_dx(rt, size_t(n) * 12);
      grid.forward_at(b_params, off, b_x, time, n, b_enc, stride, col);
      grid.backward_at(b_params, off, b_x, time, n, b_d, b_grad, off, &b_dx, false, stride, col);
      const auto row = b_enc.read_vec<float>(size_t(n) * stride);
      std::vector<float> enc;
      for (int i = 0; i < n; ++i) {
        REQUIRE(row[size_t(i) * stride + col - 1] == 5.0f);
        REQUIRE(row[size_t(i) * stride + col + w] == 5.0f);
        for (int c = 0; c < w; ++c) enc.push_back(row[size_t(i) * stride + col + c]);
      }
      CHECK(test::max_sym_rel_err(enc, test::ref::time_hash_fwd(cfg, table, x, t), 1e-2) < 1e-5);
      const auto grad = b_grad.read_vec<float>(params.size());
      CHECK(grad[off - 1] == 3.0f);  // outside the module's slice: untouched
      const std::vector<float> g_dev(grad.begin() + long(off), grad.end());
      const auto g_ref = test::ref::time_hash_bwd(cfg, table, x, t, d_enc);
      CHECK(test::max_sym_rel_err(g_dev, g_ref, 1.0) < 2e-5);
      const auto dx = b_dx.read_vec<float>(size_t(n) * 3);
      CHECK(test::max_sym_rel_err(dx, test::ref::time_hash_bwd_dx(cfg, table, x, t, d_enc), 1.0) <
            1e-5);
      grid.backward_at(b_params, off, b_x, time, n, b_d, b_grad, off, nullptr, true, stride, col);
      const auto grad2 = b_grad.read_vec<float>(params.size());
      std::vector<float> g2(grad2.begin() + long(off), grad2.end()), g2_ref(g_ref.size());
      for (size_t k = 0; k < g_ref.size(); ++k) g2_ref[k] = 2.0f * g_ref[k];
      CHECK(test::max_sym_rel_err(g2, g2_ref, 1.0) < 2e-5);
    }
    cl::Buffer b_enc(rt, size_t(n) * stride * 4);
    CHECK_THROWS_WITH(grid.forward_at(b_params, off, b_x, std::nanf(""), n, b_enc, stride, col),
                      Catch::Matchers::Contains("not a finite number"));
  }
}

TEST_CASE("time hash grid at one time: gradients agree with finite differences",
          "[field][timehash][fd]") {
  auto& rt = test::runtime();
  field::TimeHashGrid grid(rt, small_config());
  const auto& levels = grid.planes()[0].levels;
  const int n = 48, w = grid.n_output();
  const auto params = uniform(grid.n_params(), 0.2f, 1.2f, 61);
  const auto r = uniform(size_t(n) * w, -1.0f, 1.0f, 63);
  const float h = 1e-3f;
  const auto x = test::fd_points(levels, n, h, 62);
  AtTime at{grid, 0.6f};  // between slices 1 and 2 of 4
  test::check_4d_gradients(rt, at, params, x, std::vector<float>(size_t(n), 0.6f), r, w, h, 3);
}

TEST_CASE("LiDAR4D's static hash grid is the HashGrid with its sizes", "[field][timehash]") {
  const auto cfg = field::lidar4d_static_hash_config();
  const auto levels = field::hash_grid_levels(cfg);
  REQUIRE(levels.size() == 8);
  CHECK(levels[0].scale == Approx(511.0));
  CHECK(levels[7].scale == Approx(32767.0).epsilon(1e-5));
  for (const auto& lv : levels) CHECK(lv.size == (1u << 19));
  auto& rt = test::runtime();
  field::HashGrid grid(rt, cfg);
  CHECK(grid.n_output() == 32);
  const int n = 500;
  const auto table = uniform(grid.n_params(), -1.0f, 1.0f, 51);
  const auto x = uniform(size_t(n) * 3, -1.0f, 1.0f, 52);
  auto b_p = cl::Buffer::from(rt, table), b_x = cl::Buffer::from(rt, x);
  cl::Buffer b_enc(rt, size_t(n) * 32 * 4);
  grid.forward(b_p, 0, b_x, n, b_enc);
  const auto ref = test::ref::hashgrid_fwd(cfg, table, x, std::vector<float>(8, 1.0f));
  CHECK(test::max_sym_rel_err(b_enc.read_vec<float>(size_t(n) * 32), ref, 1e-2) < 1e-5);
}

TEST_CASE("time hash grid at LiDAR4D's sizes (8 levels x 4, 512..32768, 2^14/2^12) matches the "
          "reference", "[field][timehash]") {
  auto& rt = test::runtime();
  const field::TimeHashGridConfig cfg;
  field::TimeHashGrid grid(rt, cfg);
  const int n = 300, w = grid.n_output();
  REQUIRE(w == 32);
  const auto table = uniform(grid.n_params(), -1.0f, 1.0f, 71);
  const auto x = uniform(size_t(n) * 3, -1.0f, 1.0f, 72);
  const auto t = uniform(size_t(n), 0.0f, 1.0f, 73);
  const auto d_enc = uniform(size_t(n) * w, -1.0f, 1.0f, 74);
  auto b_p = cl::Buffer::from(rt, table), b_x = cl::Buffer::from(rt, x);
  auto b_t = cl::Buffer::from(rt, t), b_d = cl::Buffer::from(rt, d_enc);
  cl::Buffer b_enc(rt, size_t(n) * w * 4), b_g(rt, table.size() * 4), b_dx(rt, size_t(n) * 12);
  grid.forward(b_p, 0, b_x, b_t, n, b_enc);
  grid.backward(b_p, 0, b_x, b_t, n, b_d, b_g, 0, &b_dx);
  CHECK(test::max_sym_rel_err(b_enc.read_vec<float>(size_t(n) * w),
                              test::ref::time_hash_fwd(cfg, table, x, t), 1e-2) < 1e-5);
  CHECK(test::max_sym_rel_err(b_g.read_vec<float>(table.size()),
                              test::ref::time_hash_bwd(cfg, table, x, t, d_enc), 1e-1) < 1e-5);
  // d_x scales with the finest grid (∂pos/∂x = 16384): floor at that size.
  CHECK(test::max_sym_rel_err(b_dx.read_vec<float>(size_t(n) * 3),
                              test::ref::time_hash_bwd_dx(cfg, table, x, t, d_enc), 1e3) < 1e-5);
}
