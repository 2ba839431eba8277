// The fast renderer's grid-placed marching (render::FastRenderConfig layout "march",
// pipeline::GridMarch): the kernels against the host reference (grid_march_reference.hpp) on
// an analytic field, and LidarNerfModel::render_rays_fast with it against the protocol's
// render_rays (exact with refine 1, a full grid and no thresholds).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "pipeline/model/fast_renderer.hpp"
#include "pipeline/model/grid_march.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "pipeline/train/trainer.hpp"
#include "render/occupancy_grid.hpp"
#include "support/test_device.hpp"
#include "grid_march_reference.hpp"
#include "render_fixtures.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {

constexpr int kStride = 16;  // the density rows' width (model_detail::kDensStride)

// An analytic field: a dense slab at z = 0.15 and a ball, thin air elsewhere; its geometric
// features are the position.
float slab_logit(const float x[3]) {
  const float ball = std::sqrt((x[0] - 0.3f) * (x[0] - 0.3f) + x[1] * x[1] + x[2] * x[2]);
  if (std::fabs(x[2] - 0.15f) < 0.04f) return 3.5f;
  if (ball < 0.12f) return 2.0f;
  return -3.0f + 0.5f * x[0];
}
void slab_head(const float x[3], int r, float& a, float& b) {
  a = 2.0f * x[0] - x[1] + 0.01f * float(r);
  b = x[2] - 0.5f * x[0];
}

render::FastRenderConfig march_config(float eps, float thr) {
  render::FastRenderConfig c;
  c.layout = "march";
  c.stop_transmittance = eps;
  c.head_weight_threshold = thr;
  c.wave = 3;
  return c;
}

}  // namespace

TEST_CASE("fast render config: the layout and refine keys", "[pipeline][fast-render]") {
  const auto c = render::FastRenderConfig::from_json(Json{{"layout", "march"}, {"refine", 2}});
  CHECK(c.layout == "march");
  CHECK(c.refine == 2);
  CHECK(render::FastRenderConfig::from_json(c.to_json()).to_json() == c.to_json());
  CHECK_THROWS_WITH(render::FastRenderConfig::from_json(Json{{"layout", "grid"}}),
                    Catch::Contains("'layout' = 'grid'"));
  CHECK_THROWS_AS(render::FastRenderConfig::from_json(Json{{"refine", 0}}), ConfigError);
  // The march settings, and a file's keys over them.
  const auto m = render::FastRenderConfig::march();
  CHECK(m.layout == "march");
  CHECK(m.coarse == 2);
  const auto over = render::FastRenderConfig::from_json(Json{{"refine", 8}}, "f.json", m);
  CHECK(over.layout == "march");
  CHECK(over.refine == 8);
  CHECK(over.coarse == 2);
  CHECK(render::FastRenderConfig::from_json(Json{{"refine", 8}}).layout == "protocol");
}

TEST_CASE("grid march kernels match the host reference", "[pipeline][fast-render][device]") {
  auto& rt = test::runtime();
  const int R = 53, S = 20, cap = 24;
  Rng rng(17);
  // A grid over part of the scene box: samples beyond it (and clamped ones) take the coarse
  // spacing.
  render::GridBox box;
  box.lo = {-0.7f, -0.6f, -0.5f};
  box.hi = {0.7f, 0.6f, 0.5f};
  const std::array<int, 3> n{7, 6, 5};
  std::vector<uint8_t> cells(size_t(n[0] * n[1] * n[2]));
  for (auto& v : cells) v = rng.uniform(0, 1) < 0.5f ? 1 : 0;
  const render::OccupancyGrid g(rt, box, n, cells);
  std::vector<float> o(size_t(R) * 3), d(size_t(R) * 3);
  for (int r = 0; r < R; ++r) {
    float v[3], norm = 0.0f;
    for (int a = 0; a < 3; ++a) o[3 * size_t(r) + size_t(a)] = rng.uniform(-0.3f, 0.3f);
    for (int a = 0; a < 3; ++a) v[a] = rng.uniform(-1.0f, 1.0f), norm += v[a] * v[a];
    if (r == 0) v[0] = 0.0f, v[1] = 0.0f, v[2] = 1.0f, norm = 1.0f;  // an axis-aligned ray
    for (int a = 0; a < 3; ++a) d[3 * size_t(r) + size_t(a)] = v[a] / std::sqrt(norm);
  }
  const auto bo = cl::Buffer::from(rt, o), bd = cl::Buffer::from(rt, d);
  GridMarch::Lattice L;
  L.near = 0.02f, L.bin = 0.08f, L.bound = 0.9f, L.samples = S, L.refine = 3;
  test::MarchLattice ref_L{L.near, L.bin / float(L.refine), L.bound, L.refine, S * L.refine,
                           L.refine};
  // The callbacks compute the analytic field on the host from the device's rows.
  cl::Buffer dens(rt, size_t(R) * cap * kStride * 4), head(rt, size_t(R) * cap * 2 * 4);
  std::vector<int32_t> seen_rays;
  const auto density = [&](const cl::Buffer& x, int rows) -> const cl::Buffer& {
    const auto xs = x.read_vec<float>(size_t(rows) * 3);
    std::vector<float> out(size_t(rows) * kStride, 0.0f);
    for (int k = 0; k < rows; ++k) {
      out[size_t(k) * kStride] = slab_logit(&xs[3 * size_t(k)]);
      for (int a = 0; a < 3; ++a) out[size_t(k) * kStride + 1 + size_t(a)] = xs[3 * size_t(k) + size_t(a)];
    }
    dens.write_vec(out);
    return dens;
  };
  const auto run_head = [&](const cl::Buffer& rows_in, int rows,
                            const field::GroupIndex& index) -> const cl::Buffer& {
    const auto in = rows_in.read_vec<float>(size_t(rows) * kStride);
    const auto ray = index.point_group->read_vec<int32_t>(size_t(rows));
    std::vector<float> out(size_t(rows) * 2);
    for (int k = 0; k < rows; ++k) {
      slab_head(&in[size_t(k) * kStride + 1], ray[size_t(k)], out[2 * size_t(k)],
                out[2 * size_t(k) + 1]);
      seen_rays.push_back(ray[size_t(k)]);
    }
    head.write_vec(out);
    return head;
  };
  cl::Buffer out(rt, size_t(R) * 3 * 4);
  struct Case {
    bool median;
    float eps, thr, hit;
    int coarse = 1;
  };
  long hits_fewer = -1, all_fine = -1;
  for (const Case k : {Case{false, 0.0f, 0.0f, 0.0f}, Case{false, 0.0f, 0.0f, 1e-2f},
                       Case{false, 1e-2f, 1e-3f, 0.0f}, Case{true, 1e-2f, 1e-3f, 1e-2f},
                       Case{true, 0.0f, 1e-3f, 0.05f}, Case{false, 1e-2f, 0.0f, 1e-3f},
                       Case{false, 0.0f, 1e-3f, 1e-2f, 2}, Case{true, 1e-2f, 0.0f, 1e-2f, 3}}) {
        const bool median = k.median;
        const float eps = k.eps, thr = k.thr;
        INFO("median " << median << ", stop_transmittance " << eps << ", head threshold " << thr
                       << ", hit alpha " << k.hit);
        render::FastRenderConfig cfg = march_config(eps, thr);
        cfg.hit_alpha = k.hit;
        GridMarch::Lattice Lk = L;
        Lk.coarse = k.coarse;
        ref_L.mc = L.refine * k.coarse;
        GridMarch march(rt, R, cap, cfg);
        seen_rays.clear();
        march.render(R, bo, bd, Lk, g, median, density, run_head, out);
        const auto got = out.read_vec<float>(size_t(R) * 3);
        const test::MarchResult ref =
            test::march_reference(o, d, R, ref_L, g, eps, thr, k.hit, cfg.wave, cap, median,
                                  slab_logit, slab_head);
        CHECK(march.evaluated() == ref.evaluated);
        const GridMarch::Rows& kinds = march.rows();
        CHECK(kinds.coarse + kinds.fine + kinds.outside + kinds.dropped == march.evaluated());
        CHECK(kinds.outside > 0);
        if (k.hit > 0.0f) CHECK(kinds.dropped > 0);
        // Above the thin air's α at the coarse spacing (about 0.004), coarse rows composite.
        if (k.hit >= 1e-2f) CHECK(kinds.coarse > 0);
        if (k.hit == 0.0f) CHECK((kinds.coarse == 0 && kinds.dropped == 0 && kinds.fine > 0));
        CHECK(march.head_rows() == ref.head_rows);
        CHECK(long(seen_rays.size()) == ref.head_rows);
        CHECK(march.waves() >= 4);
        for (int ch = 0; ch < 3; ++ch) CHECK(test::worst_channel_diff(ref.out, got, ch) < 2e-5);
        if (!median && eps == 0.0f && thr == 0.0f && k.coarse == 1)
          (k.hit > 0.0f ? hits_fewer : all_fine) = march.evaluated();
  }
  // Coarse steps until a hit evaluate fewer rows than the fine walk of every occupied cell.
  INFO("rows: hit_alpha 0.01 " << hits_fewer << ", every occupied cell fine " << all_fine);
  CHECK(hits_fewer > 0);
  CHECK(hits_fewer < all_fine);
  // The walk skipped free cells: fewer rows than the lattice's points.
  render::FastRenderConfig cfg = march_config(0.0f, 0.0f);
  cfg.hit_alpha = 0.0f;
  GridMarch march(rt, R, cap, cfg);
  march.render(R, bo, bd, L, g, false, density, run_head, out);
  CHECK(march.evaluated() < long(R) * S * L.refine);
  CHECK(march.evaluated() > long(R) * S / 2);
  // Capacity is checked.
  CHECK_THROWS_AS(march.render(R + 1, bo, bd, L, g, false, density, run_head, out), Error);
}

TEST_CASE("render_rays_fast with samples placed by the grid: the protocol's with refine 1 and a "
          "full grid, close with the field's own grid",
          "[pipeline][fast-render][device]") {
  const Dataset& d = test::tiny_dataset();
  const Scene scene = make_scene(d);
  const TrainConfig c = test::tiny_config(
      Json{{"schedule", {{"iterations", 150}, {"checkpoint_every", 0}}},
           {"render", {{"n_samples", 32}, {"n_importance", 0}}}});
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), 512);
  test::opaque_state(model, scene, c, "fast_uni");
  std::vector<float> o, dir;
  image_rays(scene, normalize_pose(d.frames[13].T_world_lidar, scene.norm), 600, 1112, o, dir);
  const auto ref = model.render_rays(o, dir, 512);
  // Every cell of the scene box occupied, refine 1, no thresholds: the protocol's samples.
  render::GridBox box;
  box.lo = {-1.0f, -1.0f, -1.0f};
  box.hi = {1.0f, 1.0f, 1.0f};
  const render::OccupancyGrid full(test::runtime(), box, {4, 4, 4}, std::vector<uint8_t>(64, 1));
  render::FastRenderConfig exact_cfg = march_config(0.0f, 0.0f);
  exact_cfg.refine = 1;
  const auto exact = model.render_rays_fast(o, dir, 512, full, exact_cfg);
  CHECK(model.fast_evaluated() == 512L * 32);
  CHECK(model.fast_head_rows() <= 512L * 32);
  for (int ch = 0; ch < 3; ++ch) CHECK(test::worst_channel_diff(ref, exact, ch) < 1e-5);

  // The field's own grid, refine 4, the default thresholds: a full image renders; fewer
  // density rows than the lattice holds, and the depth close to the protocol's where both see
  // a surface.
  render::FastRenderConfig cfg = march_config(1e-4f, 1e-4f);
  cfg.cell_m = 2.0f;
  FastRenderer fast(test::runtime(), model, scene, cfg, 512);
  const RangeImage img = fast.render(d.frames[13].T_world_lidar, 13);
  CHECK(fast.counts().rays == long(img.size()));
  CHECK(fast.counts().evaluated > 0);
  CHECK(fast.counts().evaluated < long(img.size()) * 32 * cfg.refine);
  const auto fine = model.render_rays_fast(o, dir, 512, fast.grid(13), cfg);
  const float far = c.render.far_m * float(scene.norm.scale);
  int close = 0, both = 0;
  for (int r = 0; r < 512; ++r) {
    if (!(ref[3 * size_t(r) + 1] > 0.5f && fine[3 * size_t(r) + 1] > 0.5f)) continue;
    ++both;
    close += std::fabs(ref[3 * size_t(r)] - fine[3 * size_t(r)]) < 0.05f * far;
  }
  INFO(close << " of " << both << " rays with a return in both within 5 % of far");
  CHECK(both > 100);
  CHECK(close >= both * 9 / 10);
}

TEST_CASE("render_rays_fast with samples placed by the grid on LiDAR4D's 4D field: the "
          "protocol's with refine 1 and a full grid",
          "[pipeline][fast-render][lidar4d][device]") {
  const Dataset& d = test::tiny_dataset();
  const Scene scene = make_scene(d);
  const Json over{{"schedule", {{"iterations", 20}, {"checkpoint_every", 0}, {"rays_per_batch", 128},
                                {"render_chunk_rays", 512}}},
                  {"render", {{"n_samples", 16}, {"n_importance", 0}}}};
  const TrainConfig c = resolve_config("lidar4d", "smoke", over);
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), 512);
  TrainOptions opt;
  opt.run_dir = test::temp_dir("march_l4d");
  opt.seed = 3;
  opt.show_progress = false;
  train(model, scene, c, opt);
  REQUIRE(model.temporal());
  std::vector<float> o, dir;
  image_rays(scene, normalize_pose(d.frames[13].T_world_lidar, scene.norm), 600, 1112, o, dir);
  render::GridBox box;
  box.lo = {-1.0f, -1.0f, -1.0f};
  box.hi = {1.0f, 1.0f, 1.0f};
  const render::OccupancyGrid full(test::runtime(), box, {4, 4, 4}, std::vector<uint8_t>(64, 1));
  render::FastRenderConfig cfg = march_config(0.0f, 0.0f);
  cfg.refine = 1;
  // Two frame times: the march reads the field at the time set_frame set.
  std::vector<std::vector<float>> refs;
  for (const int frame : {13, 2}) {
    INFO("frame " << frame);
    model.set_frame(frame, int(d.frames.size()));
    refs.push_back(model.render_rays(o, dir, 512));
    const auto got = model.render_rays_fast(o, dir, 512, full, cfg);
    for (int ch = 0; ch < 3; ++ch) CHECK(test::worst_channel_diff(refs.back(), got, ch) < 1e-5);
  }
  CHECK(test::worst_channel_diff(refs[0], refs[1], 0) > 1e-4);  // the times differ
}
