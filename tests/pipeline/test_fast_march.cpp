// The fast renderer: the occupancy grid (host rules, dilation, build from a density function and
// from points, refusals), the marching kernels against host references, and
// LidarNerfModel::render_rays_fast against the protocol's render_rays (exact with a full grid and
// no thresholds; within the thresholds with them, on fewer samples).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "field/mlp.hpp"
#include "pipeline/model/fast_renderer.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "pipeline/train/trainer.hpp"
#include "render/occupancy_grid.hpp"
#include "support/test_device.hpp"
#include "render_fixtures.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {

// The 3³ max filter, directly.
std::vector<uint8_t> dilate_ref(const std::vector<uint8_t>& c, std::array<int, 3> n) {
  std::vector<uint8_t> out(c.size(), 0);
  const auto at = [&](int i, int j, int k) { return (size_t(k) * n[1] + size_t(j)) * n[0] + size_t(i); };
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        for (int dk = -1; dk <= 1; ++dk)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
              const int a = i + di, b = j + dj, e = k + dk;
              if (a < 0 || b < 0 || e < 0 || a >= n[0] || b >= n[1] || e >= n[2]) continue;
              if (c[at(a, b, e)]) out[at(i, j, k)] = 1;
            }
  return out;
}

// Every cell of [-1, 1]³ occupied, and a config without termination or head threshold: the fast
// renderer must then equal render_rays.
render::OccupancyGrid full_grid() {
  render::GridBox box;
  box.lo = {-1.0f, -1.0f, -1.0f};
  box.hi = {1.0f, 1.0f, 1.0f};
  return render::OccupancyGrid(test::runtime(), box, {4, 4, 4}, std::vector<uint8_t>(64, 1));
}

render::FastRenderConfig no_thresholds() {
  render::FastRenderConfig c;
  c.stop_transmittance = 0.0f;
  c.head_weight_threshold = 0.0f;
  c.wave = 5;
  return c;
}

}  // namespace

TEST_CASE("occupancy grid: dilation is the 3x3x3 max filter", "[pipeline][fast-render]") {
  const std::array<int, 3> n{7, 5, 4};
  Rng rng(5);
  std::vector<uint8_t> c(size_t(n[0] * n[1] * n[2]));
  for (auto& v : c) v = rng.uniform(0, 1) < 0.06f ? 1 : 0;
  c[0] = 1;  // a corner
  const auto one = render::dilate_cells(c, n, 1);
  CHECK(one == dilate_ref(c, n));
  CHECK(render::dilate_cells(c, n, 2) == dilate_ref(dilate_ref(c, n), n));
  CHECK(render::dilate_cells(c, n, 0) == c);
  CHECK(std::count(one.begin(), one.end(), 1) > std::count(c.begin(), c.end(), 1));
}

TEST_CASE("occupancy grid: built from the density and from points, refused when too large",
          "[pipeline][fast-render][device]") {
  auto& rt = test::runtime();
  render::FastRenderConfig cfg;
  cfg.cell_m = 1.0f, cfg.margin_m = 0.0f, cfg.dilate = 0, cfg.probes_per_axis = 2;
  cfg.alpha = 1e-3f;
  const float scale = 0.1f, delta = 0.01f;  // cells of 0.1 normalised units
  render::GridBox box;
  box.lo = {-1.0f, -0.5f, -0.2f};
  box.hi = {1.0f, 0.5f, 0.2f};
  // Dense (σ = e^5) inside a ball of radius 0.3 around (0.2, 0, 0), empty elsewhere.
  long calls = 0;
  const auto density = [&](const std::vector<float>& x, int n) {
    ++calls;
    std::vector<float> h(size_t(n), -20.0f);
    for (int p = 0; p < n; ++p) {
      const float dx = x[3 * size_t(p)] - 0.2f, dy = x[3 * size_t(p) + 1], dz = x[3 * size_t(p) + 2];
      if (dx * dx + dy * dy + dz * dz < 0.09f) h[size_t(p)] = 5.0f;
    }
    return h;
  };
  const auto g = render::OccupancyGrid::build(rt, cfg, box, scale, delta, density, 1000);
  CHECK(g.dims() == std::array<int, 3>{20, 10, 4});
  CHECK(calls > 1);  // in batches
  CHECK(g.occupied_at(0.2f, 0.0f, 0.0f));
  CHECK(g.occupied_at(0.35f, 0.1f, 0.05f));
  CHECK_FALSE(g.occupied_at(-0.8f, 0.4f, 0.1f));
  CHECK(g.occupied_at(0.2f, 0.0f, 0.5f));  // outside the box: evaluated
  CHECK(g.cell_of(-1.0f, -0.5f, -0.2f) == 0);
  CHECK(g.cell_of(1.01f, 0.0f, 0.0f) == -1);
  CHECK(g.cell_of(1.0f, 0.5f, 0.2f) == long(g.cells().size()) - 1);  // the upper corner
  // Every cell whose probes lie in the ball is occupied, no cell far from it is.
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 20; ++i) {
        const float x = -1.0f + (float(i) + 0.5f) * 0.1f, y = -0.5f + (float(j) + 0.5f) * 0.1f,
                    z = -0.2f + (float(k) + 0.5f) * 0.1f;
        const float d = std::sqrt((x - 0.2f) * (x - 0.2f) + y * y + z * z);
        if (d < 0.3f - 0.09f) CHECK(g.occupied_at(x, y, z));
        if (d > 0.3f + 0.09f) CHECK_FALSE(g.occupied_at(x, y, z));
      }
  // A threshold above the ball's density leaves it empty; points still mark their cells.
  render::FastRenderConfig high = cfg;
  high.alpha = 0.5f;
  const std::vector<float> pts{-0.75f, 0.25f, 0.05f};
  const float delta_small = 1e-4f;  // exp(5)·1e-4 < −log(0.5)
  const auto gp = render::OccupancyGrid::build(rt, high, box, scale, delta_small, density, 1000, pts);
  CHECK(gp.occupied() == 1);
  CHECK(gp.occupied_at(-0.75f, 0.25f, 0.05f));
  // Dilation grows it to its 3³ block.
  high.dilate = 1;
  CHECK(render::OccupancyGrid::build(rt, high, box, scale, delta_small, density, 1000, pts).occupied() == 27);
  // Too many cells: refused before any density call, naming the keys.
  render::FastRenderConfig tiny_cells = cfg;
  tiny_cells.cell_m = 0.01f;
  tiny_cells.max_cells = 100000;
  calls = 0;
  try {
    render::OccupancyGrid::build(rt, tiny_cells, box, scale, delta, density, 1000);
    FAIL("expected a ConfigError");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).find("max_cells") != std::string::npos);
  }
  CHECK(calls == 0);
}

TEST_CASE("fast render config: defaults, round trip, refusals", "[pipeline][fast-render]") {
  const render::FastRenderConfig d;
  CHECK(render::FastRenderConfig::from_json(d.to_json()).to_json() == d.to_json());
  // The measured defaults (docs/studies/fast-render).
  CHECK(d.cell_m == 1.0f);
  CHECK(d.probes_per_axis == 1);
  CHECK(d.max_waves == 8);
  const auto c = render::FastRenderConfig::from_json(Json{{"cell_m", 0.5}, {"wave", 8}});
  CHECK(c.cell_m == 0.5f);
  CHECK(c.wave == 8);
  CHECK_THROWS_AS(render::FastRenderConfig::from_json(Json{{"cell", 0.5}}), ConfigError);
  CHECK_THROWS_AS(render::FastRenderConfig::from_json(Json{{"alpha", 0.9}}), ConfigError);
  CHECK_THROWS_AS(render::FastRenderConfig::from_json(Json{{"wave", 0}}), ConfigError);
}

TEST_CASE("fast march kernels match the host reference", "[pipeline][fast-render][device]") {
  auto& rt = test::runtime();
  const int R = 29, S = 24;
  Rng rng(41);
  render::GridBox box;
  box.lo = {-1.0f, -1.0f, -1.0f};
  box.hi = {1.0f, 1.0f, 1.0f};
  const std::array<int, 3> n{8, 6, 5};
  std::vector<uint8_t> cells(size_t(n[0] * n[1] * n[2]));
  for (auto& v : cells) v = rng.uniform(0, 1) < 0.4f ? 1 : 0;
  const render::OccupancyGrid g(rt, box, n, cells);
  // Points inside and (some) outside the box.
  std::vector<float> x(size_t(R) * S * 3);
  for (auto& v : x) v = rng.uniform(-1.2f, 1.2f);
  auto bx = cl::Buffer::from(rt, x);
  cl::Buffer occ(rt, size_t(R) * S * 4), idx(rt, size_t(R) * S * 4), count(rt, size_t(R) * 4);
  rt.kernel("pipeline/fast_march.cl", "pipeline_grid_lookup")
      .set_args(R * S, g.lo4(), g.inv_cell4(), g.dims4(), g.device(), bx, occ)
      .launch({cl::round_up(size_t(R) * S, 64)}, {64})
      .wait();
  const auto o = occ.read_vec<int32_t>(size_t(R) * S);
  int inside = 0, outside = 0;
  for (int p = 0; p < R * S; ++p) {
    const bool e = g.occupied_at(x[3 * size_t(p)], x[3 * size_t(p) + 1], x[3 * size_t(p) + 2]);
    CHECK(o[size_t(p)] == int(e));
    inside += e;
    outside += g.cell_of(x[3 * size_t(p)], x[3 * size_t(p) + 1], x[3 * size_t(p) + 2]) < 0;
  }
  CHECK(inside > 50);
  CHECK(outside > 50);
  rt.kernel("pipeline/fast_march.cl", "pipeline_occupied_list")
      .set_args(R, S, g.lo4(), g.inv_cell4(), g.dims4(), g.device(), bx, 0, occ, idx, count)
      .launch({cl::round_up(size_t(R), 64)}, {64})
      .wait();
  const auto ix = idx.read_vec<int32_t>(size_t(R) * S), ct = count.read_vec<int32_t>(size_t(R));
  for (int r = 0; r < R; ++r) {
    std::vector<int32_t> e;
    for (int s = 0; s < S; ++s)
      if (o[size_t(r) * S + size_t(s)]) e.push_back(s);
    REQUIRE(ct[size_t(r)] == int(e.size()));
    CHECK(std::equal(e.begin(), e.end(), ix.begin() + long(r) * S));
  }
  // Termination: ray a is done once 1 − Σ_{j ≤ end} w_j < eps.
  std::vector<float> w(size_t(R) * S, 0.0f);
  std::vector<int32_t> alive, cend;
  for (int r = 0; r < R; ++r) {
    if (ct[size_t(r)] == 0) continue;
    alive.push_back(r);
    cend.push_back(1 + int(rng.next_u64() % uint64_t(ct[size_t(r)])));
    const int spike = int(rng.next_u64() % uint64_t(S));
    w[size_t(r) * S + size_t(spike)] = rng.uniform(0, 1) < 0.5f ? 1.0f : 0.5f;
  }
  const int A = int(alive.size());
  auto ba = cl::Buffer::from(rt, alive), be = cl::Buffer::from(rt, cend), bw = cl::Buffer::from(rt, w);
  cl::Buffer done(rt, size_t(A) * 4);
  rt.kernel("pipeline/fast_march.cl", "pipeline_march_done")
      .set_args(A, S, 1e-3f, ba, be, idx, bw, done)
      .launch({cl::round_up(size_t(A), 64)}, {64})
      .wait();
  const auto dn = done.read_vec<int32_t>(size_t(A));
  int n_done = 0;
  for (int a = 0; a < A; ++a) {
    const int r = alive[size_t(a)], end = ix[size_t(r) * S + size_t(cend[size_t(a)] - 1)];
    float acc = 0.0f;
    int e = 0;
    for (int j = 0; j <= end; ++j) {
      acc += w[size_t(r) * S + size_t(j)];
      if (1.0f - acc < 1e-3f) {
        e = 1;
        break;
      }
    }
    CHECK(dn[size_t(a)] == e);
    n_done += e;
  }
  CHECK(n_done > 0);
  CHECK(n_done < A);

  // The merged pass: merged samples (M per ray) whose coarse source (< S) was evaluated (its
  // logit is not the dead one) take its logit and density row and are known; the others are
  // listed when occupied.
  const int M = S + 7, stride = 3;
  std::vector<int32_t> src(size_t(R) * M);
  std::vector<float> h0c(size_t(R) * S), densc(size_t(R) * S * stride);
  for (auto& v : src) v = int32_t(rng.next_u64() % uint64_t(M));
  for (auto& v : h0c) v = rng.uniform(0, 1) < 0.3f ? -100.0f : rng.uniform(-3, 3);
  for (auto& v : densc) v = rng.uniform(-1, 1);
  std::vector<float> xm(size_t(R) * M * 3);
  for (auto& v : xm) v = rng.uniform(-1.2f, 1.2f);
  auto bsrc = cl::Buffer::from(rt, src), bh0c = cl::Buffer::from(rt, h0c),
       bdc = cl::Buffer::from(rt, densc), bxm = cl::Buffer::from(rt, xm);
  auto bh0 = cl::Buffer::from(rt, std::vector<float>(size_t(R) * M, 7.0f)),
       bdf = cl::Buffer::from(rt, std::vector<float>(size_t(R) * M * stride, 9.0f));
  cl::Buffer known(rt, size_t(R) * M * 4), idxm(rt, size_t(R) * M * 4);
  rt.kernel("pipeline/fast_march.cl", "pipeline_march_prefill")
      .set_args(R * M, S, M, stride, -100.0f, bsrc, bh0c, bdc, bh0, bdf, known)
      .launch({cl::round_up(size_t(R) * M, 64)}, {64})
      .wait();
  rt.kernel("pipeline/fast_march.cl", "pipeline_occupied_list")
      .set_args(R, M, g.lo4(), g.inv_cell4(), g.dims4(), g.device(), bxm, 1, known, idxm, count)
      .launch({cl::round_up(size_t(R), 64)}, {64})
      .wait();
  const auto kn = known.read_vec<int32_t>(size_t(R) * M), im = idxm.read_vec<int32_t>(size_t(R) * M),
             cm = count.read_vec<int32_t>(size_t(R));
  const auto h0 = bh0.read_vec<float>(size_t(R) * M), df = bdf.read_vec<float>(size_t(R) * M * stride);
  int n_known = 0, n_listed = 0;
  for (int r = 0; r < R; ++r) {
    std::vector<int32_t> e;
    for (int m = 0; m < M; ++m) {
      const size_t q = size_t(r) * M + size_t(m);
      const int s = src[q];
      const bool k = s < S && h0c[size_t(r) * S + size_t(s)] != -100.0f;
      REQUIRE(kn[q] == int(k));
      n_known += k;
      for (int j = 0; j < stride; ++j)
        CHECK(df[q * stride + size_t(j)] ==
              (k ? densc[(size_t(r) * S + size_t(s)) * stride + size_t(j)] : 9.0f));
      CHECK(h0[q] == (k ? h0c[size_t(r) * S + size_t(s)] : 7.0f));
      if (!k && g.occupied_at(xm[3 * q], xm[3 * q + 1], xm[3 * q + 2])) e.push_back(m);
    }
    REQUIRE(cm[size_t(r)] == int(e.size()));
    CHECK(std::equal(e.begin(), e.end(), im.begin() + long(r) * M));
    n_listed += int(e.size());
  }
  CHECK(n_known > 50);
  CHECK(n_listed > 50);
}

TEST_CASE("render_rays_fast: exact with a full grid and no thresholds, close and cheaper with them",
          "[pipeline][fast-render][device]") {
  const Dataset& d = test::tiny_dataset();
  const Scene scene = make_scene(d);
  for (const bool importance : {true, false}) {
    INFO("importance sampling " << importance);
    const TrainConfig c = test::tiny_config(
        Json{{"schedule", {{"iterations", 150}, {"checkpoint_every", 0}}},
             {"render", {{"n_samples", importance ? 16 : 32}, {"n_importance", importance ? 4 : 0}}}});
    LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), 512);
    // Opaque surfaces, so that the thresholds below cut something.
    test::opaque_state(model, scene, c, importance ? "fast_imp" : "fast_uni");
    std::vector<float> o, dir;
    image_rays(scene, normalize_pose(d.frames[13].T_world_lidar, scene.norm), 600, 1112, o, dir);
    const auto ref = model.render_rays(o, dir, 512);
    // Every cell occupied, no termination, the head wherever the weight is positive.
    const render::OccupancyGrid full = full_grid();
    const render::FastRenderConfig none = no_thresholds();
    const auto exact = model.render_rays_fast(o, dir, 512, full, none);
    const int M = c.render.n_samples + c.render.n_importance;
    // The merged pass evaluates only the importance samples: as many rows as the protocol's.
    CHECK(model.fast_evaluated() == 512L * M);
    for (int ch = 0; ch < 3; ++ch) CHECK(test::worst_channel_diff(ref, exact, ch) < 1e-5);

    // Termination and the head threshold (full grid): fewer rows; the depth moves by at most
    // about the weight left behind termination times the far plane, the probability by at
    // most the weight of the samples the head skips (each below the threshold).
    render::FastRenderConfig cut = none;
    cut.stop_transmittance = 1e-3f;
    cut.head_weight_threshold = 1e-3f;
    const auto approx = model.render_rays_fast(o, dir, 512, full, cut);
    const long full_rows = 512L * M;
    INFO("density rows " << model.fast_evaluated() << " of " << full_rows << ", head rows "
                         << model.fast_head_rows() << " of " << 512L * M);
    CHECK(model.fast_evaluated() < full_rows);
    CHECK(model.fast_head_rows() < 512L * M * 3 / 4);
    const float far = c.render.far_m * float(scene.norm.scale);
    const double dd = test::worst_channel_diff(ref, approx, 0), dp = test::worst_channel_diff(ref, approx, 1);
    INFO("worst |depth diff| " << dd << " (far " << far << "), worst |prob diff| " << dp);
    if (importance) {
      // The importance pdf moves with the coarse weights behind termination: bounded loosely.
      CHECK(dd < 0.05 * far);
    } else {
      CHECK(dd <= 4 * cut.stop_transmittance * far);
    }
    CHECK(dp <= double(M) * cut.head_weight_threshold + 4 * cut.stop_transmittance);

    // The field's own grid (FastRenderer): built once, a frame renders through it.
    render::FastRenderConfig cfg;
    cfg.cell_m = 2.0f;
    FastRenderer fast(test::runtime(), model, scene, cfg, 512);
    const render::OccupancyGrid& g = fast.grid(13);
    CHECK(&fast.grid(13) == &g);
    CHECK(g.occupied_fraction() > 0.0);
    // A full image through the FastRenderer equals the chunked render_rays_fast.
    const RangeImage img = fast.render(d.frames[13].T_world_lidar, 13);
    CHECK(fast.counts().frames == 1);
    CHECK(fast.counts().rays == long(img.size()));
    CHECK(fast.counts().evaluated > 0);
  }
}

TEST_CASE("render_rays_fast on LiDAR4D's 4D field: exact with a full grid and no thresholds",
          "[pipeline][fast-render][lidar4d][device]") {
  const Dataset& d = test::tiny_dataset();
  const Scene scene = make_scene(d);
  const TrainConfig c = resolve_config(
      "lidar4d", "smoke",
      Json{{"schedule", {{"iterations", 20}, {"checkpoint_every", 0}, {"rays_per_batch", 128},
                         {"render_chunk_rays", 512}}},
           {"render", {{"n_samples", 16}, {"n_importance", 4}}}});
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), 512);
  TrainOptions opt;
  opt.run_dir = test::temp_dir("fast_l4d");
  opt.seed = 3;
  opt.show_progress = false;
  train(model, scene, c, opt);
  REQUIRE(model.temporal());
  model.set_frame(13, int(d.frames.size()));
  std::vector<float> o, dir;
  image_rays(scene, normalize_pose(d.frames[13].T_world_lidar, scene.norm), 600, 1112, o, dir);
  const auto ref = model.render_rays(o, dir, 512);
  const render::OccupancyGrid full = full_grid();
  const render::FastRenderConfig none = no_thresholds();
  const auto exact = model.render_rays_fast(o, dir, 512, full, none);
  for (int ch = 0; ch < 3; ++ch) CHECK(test::worst_channel_diff(ref, exact, ch) < 1e-5);
  // The FastRenderer's grid at frame 13 leaves the time at frame 13.
  FastRenderer fast(test::runtime(), model, scene, render::FastRenderConfig{}, 512);
  fast.grid(5);
  model.set_frame(13, int(d.frames.size()));
  const auto again = model.render_rays(o, dir, 512);
  CHECK(again == ref);
}
