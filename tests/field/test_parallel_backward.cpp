// The encoders' parallel parameter backwards (cl::EncoderBackward): the entry reduction on its
// own against an in-order host sum; for the hash grid, the time hash grid (per-point times and
// one time for all) and K-Planes (both groups and each alone, accumulate), the deterministic
// parallel backward bit-identical to the serial one and the atomic one within float rounding of
// it, both against the host references; and finite differences of the device forward.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include "core/rng.hpp"
#include "fd_4d.hpp"
#include "field/entry_reduction.hpp"
#include "field/hash_grid.hpp"
#include "field/kplanes.hpp"
#include "field/time_hash_grid.hpp"
#include "reference.hpp"
#include "reference_4d.hpp"
#include "support/test_device.hpp"
#include "support/device_tolerance.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using sgnlf::test::same_bits;
using cl::EncoderBackward;
using field::PlaneGroups;
using test::uniform;

namespace {
const EncoderBackward kParallel[] = {EncoderBackward::DeterministicParallel,
                                     EncoderBackward::Atomic};

field::HashGridConfig grid_config() {  // res 5, 9 dense; 17, 33 hashed into 4096 entries
  field::HashGridConfig c;
  c.levels = 4;
  c.features = 2;
  c.log2_table_size = 12;
  c.base_resolution = 4.0f;
  c.per_level_scale = 2.0f;
  return c;
}
field::TimeHashGridConfig time_config() {  // as tests/field/test_time_hash_grid.cpp
  field::TimeHashGridConfig c;
  c.levels = 3;
  c.features = 2;
  c.time_slices = 4;
  c.base_resolution = 4.0f;
  c.per_level_scale = 2.0f;
  c.log2_table_xy = 7;
  c.log2_table_xz = 6;
  c.log2_table_yz = 6;
  return c;
}
field::KPlanesConfig planes_config() {
  field::KPlanesConfig c;
  c.resolution = 5;
  c.scales = 2;
  c.time_resolution = 3;
  c.features = 2;
  return c;
}
}  // namespace

namespace {
void check_entry_reduction(int n = 700);
}

// At the profile's radix tile (256 under the cpu profile, 16 under the gpu one: Oclgrind's).
TEST_CASE("entry reduction sums each entry's pairs in pair order", "[field][parallel_bwd]") {
  check_entry_reduction();
}

// At the cpu profile's radix tile (256), 16, one pair per work-item and an odd tile, and with a
// minimum of work-items that halves the tile (to 32 and to 4 here: 4200 pairs a unit; the
// histogram then scanned in 2 and 16 blocks, field::RadixScan): the sort is stable at any tile
// and the scan's sums are integers, so each gives the host's in-order sums bit for bit.
TEST_CASE("entry reduction gives the same sums at any radix tile",
          "[field][parallel_bwd][radix_tiles]") {
  const auto [tile, min_wi] =
      GENERATE(std::make_pair(256, 0), std::make_pair(16, 0), std::make_pair(1, 0),
               std::make_pair(37, 0), std::make_pair(256, 200), std::make_pair(256, 3000));
  INFO("radix_tile " << tile << ", radix_min_work_items " << min_wi);
  cl::DeviceProfile profile = test::runtime().device_profile();
  profile.radix_tile = tile;
  profile.radix_min_work_items = min_wi;
  test::ProfileScope scope(profile);
  check_entry_reduction();
}

// Halved tiles on fewer points (oclgrind_field_parallel, which runs the encoders' cases at the
// full tile: at 16 they took 177 s there instead of 84): 360 pairs a unit, tiles of 16 and 2.
TEST_CASE("entry reduction at small radix tiles on a small case",
          "[field][parallel_bwd][radix_tiles][small]") {
  const int min_wi = GENERATE(60, 500);
  INFO("radix_min_work_items " << min_wi);
  cl::DeviceProfile profile = test::runtime().device_profile();
  profile.radix_tile = 256;
  profile.radix_min_work_items = min_wi;
  test::ProfileScope scope(profile);
  check_entry_reduction(60);
}

namespace {
void check_entry_reduction(const int n) {
  auto& rt = test::runtime();
  // 3 units; unit u owns entries [u·40 + 5, +30) and unit 1 also [200, 210); 6 pairs per point
  // in vectors of 3; keys drawn from few entries (long runs) and others (short ones).
  const int units = 3, P = 6, PV = 3, F = 4;
  std::vector<field::EntryRange> ranges = {{0, 5, 30}, {1, 45, 30}, {2, 85, 30}, {1, 200, 10}};
  field::EntryReduction red(rt, F, units, P, PV, ranges);
  CHECK(red.entries() == 100);
  CHECK(red.passes() == 2);  // entries < 256
  Rng rng(5);
  const size_t m = size_t(n) * P;
  std::vector<uint32_t> keys(m * units), vals(m * units);
  for (int u = 0; u < units; ++u)
    for (size_t j = 0; j < m; ++j) {
      const uint32_t r = rng.next_u32();
      uint32_t key;
      if (u == 1 && r % 5 == 0) key = 200 + (r >> 8) % 10;
      else key = uint32_t(u) * 40 + 5 + ((r % 3 == 0) ? (r >> 8) % 3 : (r >> 8) % 30);
      keys[size_t(u) * m + j] = key;
      vals[size_t(u) * m + j] = uint32_t(j);
    }
  const auto coef = uniform(m * units, -1.0f, 1.0f, 6);
  const auto vec = uniform(m * units / PV * F, -1.0f, 1.0f, 7);
  const size_t goff = 3, total = goff + 210 * F + 8;
  const auto init = uniform(total, -2.0f, 2.0f, 8);
  // Host: per unit, in pair order, fma into each owned entry.
  auto host = [&](bool accumulate) {
    std::vector<float> g = init;
    for (const auto& r : ranges)
      for (uint32_t e = r.first; e < r.first + r.count; ++e)
        for (int f = 0; f < F; ++f) {
          float acc = accumulate ? init[goff + e * F + f] : 0.0f;
          for (size_t j = 0; j < m; ++j) {
            const size_t pair = size_t(r.unit) * m + j;
            if (keys[pair] != e) continue;
            acc = std::fma(coef[pair], vec[pair / PV * F + f], acc);
          }
          g[goff + e * F + f] = acc;
        }
    return g;
  };
  for (bool accumulate : {false, true}) {
    INFO("accumulate " << accumulate);
    red.reserve(n);
    red.keys().write_vec(keys);
    red.vals().write_vec(vals);
    red.coef().write_vec(coef);
    red.vec().write_vec(vec);
    auto b_grad = cl::Buffer::from(rt, init);
    red.reduce(n, b_grad, goff, accumulate);
    const auto g = b_grad.read_vec<float>(total);
    const auto ref = host(accumulate);
    CHECK(same_bits(g, ref));  // entries outside the ranges keep their values
    CHECK(g[goff + 0] == init[goff + 0]);
    CHECK(g[goff + 200 * F - 1] == init[goff + 200 * F - 1]);
  }
  auto b_grad = cl::Buffer::from(rt, init);
  red.zero(b_grad, goff);
  const auto z = b_grad.read_vec<float>(total);
  CHECK(z[goff + 5 * F] == 0.0f);
  CHECK(z[goff + 209 * F + 3] == 0.0f);
  CHECK(z[goff + 5 * F - 1] == init[goff + 5 * F - 1]);
  CHECK(z[goff + 35 * F] == init[goff + 35 * F]);
  CHECK_THROWS_WITH(field::EntryReduction(rt, F, 2, 6, 4, ranges),
                    Catch::Matchers::Contains("must divide"));
  CHECK_THROWS_WITH(field::EntryReduction(rt, F, 3, 6, 3, {{0, 5, 30}, {1, 20, 30}}),
                    Catch::Matchers::Contains("overlap"));
  CHECK_THROWS_WITH(red.reduce(n + 1, b_grad, goff, false),
                    Catch::Matchers::Contains("reserve first"));
}
}  // namespace

TEST_CASE("hash grid parallel backwards: deterministic = serial bit for bit, atomic within "
          "rounding, both match the host reference",
          "[field][parallel_bwd][hashgrid]") {
  auto& rt = test::runtime();
  const auto cfg = grid_config();
  field::HashGrid grid(rt, cfg);
  const int n = 1500, lf = grid.n_output();
  const size_t off = 32;
  const auto table = uniform(grid.n_params(), -1.0f, 1.0f, 11);
  std::vector<float> params(off, 0.0f);
  params.insert(params.end(), table.begin(), table.end());
  const auto x = uniform(size_t(n) * 3, -1.1f, 1.1f, 12);  // clamped dense and wrapped hashes
  const auto d_enc = uniform(size_t(n) * lf, -1.0f, 1.0f, 13);
  const std::vector<float> weights = {1.0f, 0.75f, 0.25f, 0.0f};
  grid.set_level_weights(weights);
  auto b_params = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, x);
  auto b_denc = cl::Buffer::from(rt, d_enc);
  auto run = [&](EncoderBackward v, std::vector<float>& dx) {
    grid.set_backward(v);
    auto b_grad = cl::Buffer::from(rt, std::vector<float>(params.size(), 3.0f));
    cl::Buffer b_dx(rt, size_t(n) * 12);
    grid.backward(b_params, off, b_x, n, b_denc, b_grad, off, &b_dx);
    dx = b_dx.read_vec<float>(size_t(n) * 3);
    return b_grad.read_vec<float>(params.size());
  };
  std::vector<float> dx_serial;
  const auto serial = run(EncoderBackward::Serial, dx_serial);
  const auto g_ref = test::ref::hashgrid_bwd(cfg, grid.n_params(), x, weights, d_enc);
  for (EncoderBackward v : kParallel) {
    INFO(cl::encoder_backward_name(v));
    std::vector<float> dx;
    const auto g = run(v, dx);
    CHECK(g[off - 1] == 3.0f);
    CHECK(same_bits(dx, dx_serial));  // d_x does not depend on the variant
    const std::vector<float> g_dev(g.begin() + long(off), g.end());
    CHECK(test::max_sym_rel_err(g_dev, g_ref, 1.0) < 1e-5);
    if (v == EncoderBackward::DeterministicParallel) {
      CHECK(same_bits(g, serial));
      std::vector<float> dx2;
      CHECK(same_bits(run(v, dx2), g));  // and again
    } else {
      CHECK(test::max_sym_rel_err(g, serial, 1.0) < 1e-5);
    }
  }
  // No points: the slice is zeroed by every variant.
  for (EncoderBackward v : kParallel) {
    grid.set_backward(v);
    auto b_grad = cl::Buffer::from(rt, std::vector<float>(params.size(), 3.0f));
    grid.backward(b_params, off, b_x, 0, b_denc, b_grad, off);
    const auto g = b_grad.read_vec<float>(params.size());
    CHECK(std::all_of(g.begin() + long(off), g.end(), [](float f) { return f == 0.0f; }));
  }
}

TEST_CASE("time hash grid parallel backwards: deterministic = serial bit for bit, atomic "
          "within rounding, both match the host reference",
          "[field][parallel_bwd][timehash]") {
  auto& rt = test::runtime();
  for (int slices : {4, 1}) {
    auto cfg = time_config();
    cfg.time_slices = slices;
    field::TimeHashGrid grid(rt, cfg);
    const int n = 600, w = grid.n_output(), stride = w + 2, col = 1;
    const size_t off = 32;
    const auto table = uniform(grid.n_params(), -1.0f, 1.0f, 11);
    std::vector<float> params(off, 0.0f);
    params.insert(params.end(), table.begin(), table.end());
    const auto x = uniform(size_t(n) * 3, -1.1f, 1.1f, 12);
    auto t = uniform(size_t(n), -0.1f, 1.1f, 14);
    t[0] = 0.0f;  // on slices, and the last one (s0 = s1)
    t[1] = 1.0f / 3.0f;
    t[2] = 1.0f;
    const auto d_enc = uniform(size_t(n) * w, -1.0f, 1.0f, 13);
    std::vector<float> d_row(size_t(n) * stride, 9.0f);
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < w; ++c) d_row[size_t(i) * stride + col + c] = d_enc[size_t(i) * w + c];
    auto b_params = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, x);
    auto b_t = cl::Buffer::from(rt, t), b_d = cl::Buffer::from(rt, d_row);
    // Per-point times (at_time < 0) or one time for all; a backward, then one accumulated.
    auto run = [&](EncoderBackward v, float at_time, std::vector<float>& dx,
                   std::vector<float>& twice) {
      grid.set_backward(v);
      auto b_grad = cl::Buffer::from(rt, std::vector<float>(params.size(), 3.0f));
      cl::Buffer b_dx(rt, size_t(n) * 12);
      if (at_time < 0) {
        grid.backward(b_params, off, b_x, b_t, n, b_d, b_grad, off, &b_dx, false, stride, col);
      } else {
        grid.backward_at(b_params, off, b_x, at_time, n, b_d, b_grad, off, &b_dx, false, stride,
                         col);
      }
      const auto g = b_grad.read_vec<float>(params.size());
      dx = b_dx.read_vec<float>(size_t(n) * 3);
      if (at_time < 0)
        grid.backward(b_params, off, b_x, b_t, n, b_d, b_grad, off, nullptr, true, stride, col);
      else
        grid.backward_at(b_params, off, b_x, at_time, n, b_d, b_grad, off, nullptr, true,
                         stride, col);
      twice = b_grad.read_vec<float>(params.size());
      return g;
    };
    for (float at_time : {-1.0f, 0.55f}) {
      INFO("slices " << slices << ", time " << (at_time < 0 ? "per point" : "one") << " "
                     << at_time);
      const auto t_ref = at_time < 0 ? t : std::vector<float>(size_t(n), at_time);
      const auto g_ref = test::ref::time_hash_bwd(cfg, table, x, t_ref, d_enc);
      std::vector<float> dx_serial, twice_serial;
      const auto serial = run(EncoderBackward::Serial, at_time, dx_serial, twice_serial);
      for (EncoderBackward v : kParallel) {
        INFO(cl::encoder_backward_name(v));
        std::vector<float> dx, twice;
        const auto g = run(v, at_time, dx, twice);
        CHECK(g[off - 1] == 3.0f);
        CHECK(same_bits(dx, dx_serial));
        const std::vector<float> g_dev(g.begin() + long(off), g.end());
        CHECK(test::max_sym_rel_err(g_dev, g_ref, 1.0) < 2e-5);
        if (v == EncoderBackward::DeterministicParallel) {
          CHECK(same_bits(g, serial));
          CHECK(same_bits(twice, twice_serial));
        } else {
          CHECK(test::max_sym_rel_err(g, serial, 1.0) < 1e-5);
          CHECK(test::max_sym_rel_err(twice, twice_serial, 1.0) < 1e-5);
        }
      }
    }
  }
}

TEST_CASE("kplanes parallel backwards: deterministic = serial bit for bit, atomic within "
          "rounding, both match the host reference",
          "[field][parallel_bwd][kplanes]") {
  auto& rt = test::runtime();
  const auto cfg = planes_config();
  field::KPlanes kp(rt, cfg);
  for (PlaneGroups groups : {PlaneGroups::Both, PlaneGroups::Static, PlaneGroups::Dynamic}) {
    const int n = 600, w = kp.n_output(groups), stride = w + 3, col = 2;
    const size_t off = 16;
    const auto table = uniform(kp.n_params(), -1.0f, 1.0f, 11);
    std::vector<float> params(off, 0.0f);
    params.insert(params.end(), table.begin(), table.end());
    const auto x = uniform(size_t(n) * 3, -1.1f, 1.1f, 12);
    const auto t = uniform(size_t(n), -0.1f, 1.1f, 14);
    const auto d_enc = uniform(size_t(n) * w, -1.0f, 1.0f, 13);
    std::vector<float> d_row(size_t(n) * stride, 9.0f);
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < w; ++c) d_row[size_t(i) * stride + col + c] = d_enc[size_t(i) * w + c];
    auto b_params = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, x);
    auto b_t = cl::Buffer::from(rt, t), b_d = cl::Buffer::from(rt, d_row);
    auto run = [&](EncoderBackward v, std::vector<float>& dx, std::vector<float>& twice) {
      kp.set_backward(v);
      auto b_grad = cl::Buffer::from(rt, std::vector<float>(params.size(), 3.0f));
      cl::Buffer b_dx(rt, size_t(n) * 12);
      kp.backward(b_params, off, b_x, b_t, n, b_d, b_grad, off, &b_dx, groups, false, stride,
                  col);
      const auto g = b_grad.read_vec<float>(params.size());
      dx = b_dx.read_vec<float>(size_t(n) * 3);
      kp.backward(b_params, off, b_x, b_t, n, b_d, b_grad, off, nullptr, groups, true, stride,
                  col);
      twice = b_grad.read_vec<float>(params.size());
      return g;
    };
    auto g_ref = test::ref::kplanes_bwd(cfg, table, x, t, d_enc, groups);
    for (const auto& pl : kp.planes())  // the other group's planes keep their (stale) values
      if (groups != PlaneGroups::Both && (pl.plane >= 3) != (groups == PlaneGroups::Dynamic))
        for (size_t e = 0; e < size_t(pl.width) * pl.height * 2; ++e)
          g_ref[size_t(pl.offset) * 2 + e] = 3.0f;
    std::vector<float> dx_serial, twice_serial;
    const auto serial = run(EncoderBackward::Serial, dx_serial, twice_serial);
    for (EncoderBackward v : kParallel) {
      INFO(cl::encoder_backward_name(v) << ", groups " << int(groups));
      std::vector<float> dx, twice;
      const auto g = run(v, dx, twice);
      CHECK(same_bits(dx, dx_serial));
      const std::vector<float> g_dev(g.begin() + long(off), g.end());
      CHECK(test::max_sym_rel_err(g_dev, g_ref, 1.0) < 2e-5);  // stale planes exactly 3
      if (v == EncoderBackward::DeterministicParallel) {
        CHECK(same_bits(g, serial));
        CHECK(same_bits(twice, twice_serial));
      } else {
        CHECK(test::max_sym_rel_err(g, serial, 1.0) < 1e-5);
        CHECK(test::max_sym_rel_err(twice, twice_serial, 1.0) < 1e-5);
      }
    }
  }
}

TEST_CASE("parallel backwards agree with finite differences of the device forward",
          "[field][parallel_bwd][fd]") {
  auto& rt = test::runtime();
  for (EncoderBackward v : kParallel) {
    INFO(cl::encoder_backward_name(v));
    {  // time hash grid
      field::TimeHashGrid grid(rt, time_config());
      grid.set_backward(v);
      const int n = 48, w = grid.n_output();
      const auto params = uniform(grid.n_params(), 0.2f, 1.2f, 21);
      const auto r = uniform(size_t(n) * w, -1.0f, 1.0f, 23);
      const auto t = uniform(size_t(n), 0.0f, 1.0f, 24);
      const float h = 1e-3f;
      const auto x = test::fd_points(grid.planes()[0].levels, n, h, 22);
      test::check_4d_gradients(rt, grid, params, x, t, r, w, h, 5);
    }
    {  // K-Planes: points away from every cell face
      const auto cfg = planes_config();
      field::KPlanes kp(rt, cfg);
      kp.set_backward(v);
      const int n = 48, w = kp.n_output();
      const auto params = uniform(kp.n_params(), 0.2f, 1.2f, 21);
      const auto r = uniform(size_t(n) * w, -1.0f, 1.0f, 23);
      const auto t = uniform(size_t(n), 0.0f, 1.0f, 24);
      const float h = 1e-3f;
      std::vector<float> x;
      Rng rng(22);
      while (x.size() < size_t(n) * 3) {
        float p[3];
        bool ok = true;
        for (float& c : p) {
          c = rng.uniform(-0.95f, 0.95f);
          for (int s = 0; s < cfg.scales; ++s) {
            const double span = double(cfg.resolution << s) - 1.0, pos = (c + 1.0) * 0.5 * span;
            const double fr = pos - std::floor(pos), mg = 4 * h * 0.5 * span;
            ok = ok && fr > mg && fr < 1 - mg;
          }
        }
        if (ok) x.insert(x.end(), p, p + 3);
      }
      test::check_4d_gradients(rt, kp, params, x, t, r, w, h, 7);
    }
    {  // hash grid: L = Σ r · enc is linear in the table
      const auto cfg = grid_config();
      field::HashGrid grid(rt, cfg);
      grid.set_backward(v);
      const int n = 64, lf = grid.n_output();
      const auto params = uniform(grid.n_params(), -1.0f, 1.0f, 21);
      const auto r = uniform(size_t(n) * lf, -1.0f, 1.0f, 23);
      const auto x = test::fd_points(field::hash_grid_levels(cfg), n, 1e-3f, 22);
      grid.set_level_weights({1.0f, 0.5f, 1.0f, 0.8f});
      auto b_params = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, x);
      auto b_r = cl::Buffer::from(rt, r);
      cl::Buffer b_enc(rt, size_t(n) * lf * 4), b_grad(rt, params.size() * 4);
      grid.backward(b_params, 0, b_x, n, b_r, b_grad, 0);
      const auto grad = b_grad.read_vec<float>(params.size());
      auto loss = [&](const std::vector<float>& p) {
        b_params.write_vec(p);
        grid.forward(b_params, 0, b_x, n, b_enc);
        return test::dot(b_enc.read_vec<float>(size_t(n) * lf), r);
      };
      std::vector<float> fd, an;
      for (size_t k = 0; k < grad.size() && fd.size() < 40; k += 97) {
        if (grad[k] == 0.0f) continue;
        auto p = params;
        p[k] += 0.5f;
        const double lp = loss(p);
        p[k] -= 1.0f;
        fd.push_back(float(lp - loss(p)));
        an.push_back(grad[k]);
      }
      REQUIRE(fd.size() >= 20);
      CHECK(test::max_sym_rel_err(fd, an, 1e-3) < 1e-3);
    }
  }
}
