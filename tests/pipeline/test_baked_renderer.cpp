// The baked renderer's field head (pipeline::BakedRenderer, docs/baking.md): a ray whose weight
// lies within head_spread_m takes the head once at its surface point; a ray whose weight spreads
// takes it at each of the weight's quartiles (bake::RayCaster's outputs), equally weighted, and
// that quadrature is close to the head summed over every sample's weight, as the field's
// renderer sums it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "bake/bake.hpp"
#include "bake/ray_caster.hpp"
#include "pipeline/model/baked_renderer.hpp"
#include "pipeline/model/view_rules.hpp"
#include "support/test_device.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {

// A translucent slab along +x from 4 to 14 m in front of `o` (σ 0.35/m: the weight spreads over
// metres, as on a far surface a field keeps soft), nothing elsewhere.
bake::BakedScene soft_slab(const Eigen::Vector3d& o) {
  bake::BakeInput in;
  for (float x = 4.0f; x <= 14.0f; x += 0.25f)
    for (float y = -1.0f; y <= 1.0f; y += 0.5f)
      for (float z = -1.0f; z <= 1.0f; z += 0.5f)
        in.returns_m.insert(in.returns_m.end(), {float(o.x()) + x, float(o.y()) + y, float(o.z()) + z});
  in.origins_m = {float(o.x()), float(o.y()), float(o.z())};
  in.near_m = 0.5f, in.far_m = 30.0f;
  bake::FieldProbe p;
  const float ox = float(o.x());
  p.density = [ox](const std::vector<float>& x, int n) {
    std::vector<float> l(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      const float xi = x[3 * size_t(i)] - ox;
      l[size_t(i)] = xi >= 4.0f && xi <= 14.0f ? std::log(0.35f) : -20.0f;
    }
    return l;
  };
  p.head = [](const std::vector<float>&, const std::vector<float>&, int n) {
    return std::vector<float>(size_t(n) * 2, 0.5f);
  };
  bake::BakeConfig c;
  c.voxel_m = 0.2f;
  c.brick = 4;
  c.dilate_m = 0.3f;
  return bake::bake_field(c, in, p);
}

// The head's return probability and intensity at world points along `d` from the scene's centre.
std::vector<float> head(LidarNerfModel& m, const Scene& view, const float* d,
                        const std::vector<float>& t) {
  std::vector<float> x, dir;
  for (float ti : t)
    for (size_t a = 0; a < 3; ++a) {
      x.push_back(std::clamp(float(double(d[a]) * ti * view.norm.scale), -1.0f, 1.0f));
      dir.push_back(d[a]);
    }
  return m.head_at(x, dir, int(t.size()));
}

// The tiny scene's sensor at its centre, the slab in front of it: the view, its pose, the
// slab and the caster's outputs for every pixel (what the renderers are checked against).
struct SlabView {
  Scene view = make_scene(test::tiny_dataset());
  Pose T = Pose::Identity();
  bake::BakedScene slab;
  std::vector<float> cast;
  size_t n = 0;
  SlabView() {
    const Eigen::Vector3d centre = view.norm.center;
    T.translation() = centre;
    slab = soft_slab(centre);
    n = view.directions.size() / 3;
    std::vector<float> origins(n * 3);
    for (size_t p = 0; p < n; ++p)
      for (size_t a = 0; a < 3; ++a) origins[3 * p + a] = float(centre[long(a)]);
    cast = bake::RayCaster(test::runtime(), slab).cast(origins, view.directions);
  }
};

}  // namespace

TEST_CASE("baked renderer, field head: one row at the surface point, or the quartiles where the weight spreads",
          "[pipeline][bake]") {
  const SlabView sv;
  const Scene& view = sv.view;
  const TrainConfig c = test::tiny_config();
  LidarNerfModel model(test::runtime(), c, float(view.norm.scale), model_capacity(c));
  model.init_params(11);
  // A head that varies along the rays: the hash grid's entries far from their ±1e-4 start.
  std::vector<float> params = model.params();
  const field::ParamSlice grid = model.layout().slice("hash_grid");
  const std::vector<float> u = test::uniform(grid.count, -0.5f, 0.5f, 5);
  std::copy(u.begin(), u.end(), params.begin() + long(grid.offset));
  model.set_params(params);
  const bake::BakedScene& slab = sv.slab;
  const Pose& T = sv.T;
  const size_t n = sv.n;
  const std::vector<float>& cast = sv.cast;
  constexpr size_t K = bake::RayCaster::kOutputs;

  const render::RenderConfig expected = c.render;  // the smoke preset's: expected depth
  REQUIRE(expected.eval_depth == "expected");
  BakedRenderer quartiles(test::runtime(), slab, expected, &model);        // the scene's voxel
  BakedRenderer one_point(test::runtime(), slab, expected, &model, 1e9f);  // never spread
  DepthStats stats;
  const RangeImage q = quartiles.render(T, view, &stats);
  const RangeImage o = one_point.render(T, view);
  const std::vector<float>& opacity = stats.opacity;
  REQUIRE(opacity.size() == n);
  long hits = 0, spread = 0;
  double err_q = 0.0, err_o = 0.0;
  for (size_t p = 0; p < n; ++p) {
    const float* r = &cast[K * p];
    CHECK(opacity[p] == r[3]);
    const float* d = &view.directions[3 * p];
    // Rays along +x that stay inside the slab's bricks to its end (|y|, |z| < 0.7 m at 14 m).
    if (!(r[3] > 0.5f) || d[0] < 0.99f || std::abs(d[1]) > 0.05f || std::abs(d[2]) > 0.05f) continue;
    ++hits;
    // One point: the head at o + d·depth/opacity, times the opacity.
    const auto h1 = head(model, view, d, {r[0] / r[3]});
    CHECK(o.ray_drop[p] == Approx(r[3] * h1[0]).margin(1e-5));
    CHECK(o.intensity[p] == Approx(r[3] * h1[1]).margin(1e-5));
    // The quartiles: every level reached (opacity > 7/8 here), metres apart.
    REQUIRE(r[7] >= 0.0f);
    CHECK(r[7] - r[4] > 1.0f);
    ++spread;
    const auto hq = head(model, view, d, {r[4], r[5], r[6], r[7]});
    CHECK(q.ray_drop[p] == Approx(r[3] * (hq[0] + hq[2] + hq[4] + hq[6]) / 4.0f).margin(1e-5));
    CHECK(q.intensity[p] == Approx(r[3] * (hq[1] + hq[3] + hq[5] + hq[7]) / 4.0f).margin(1e-5));
    // The field renderer's sum over the weight, densely: w(t) = σ e^(−σ (t − 4)) dt on the slab.
    std::vector<float> t;
    std::vector<double> w;
    const float sigma = 0.35f, dt = 0.05f;
    const float t_in = 4.0f / std::max(d[0], 1e-6f), t_out = std::min(14.0f / std::max(d[0], 1e-6f), 30.0f);
    for (float s = t_in + 0.5f * dt; s < t_out; s += dt) {
      t.push_back(s);
      w.push_back(sigma * std::exp(-sigma * (s - t_in)) * dt);
    }
    const auto hd = head(model, view, d, t);
    double dense = 0.0, wsum = 0.0;
    for (size_t k = 0; k < t.size(); ++k) dense += w[k] * hd[2 * k], wsum += w[k];
    dense *= double(r[3]) / wsum;
    err_q += std::abs(double(q.ray_drop[p]) - dense);
    err_o += std::abs(double(o.ray_drop[p]) - dense);
  }
  REQUIRE(hits > 0);
  CHECK(spread == hits);
  CHECK(quartiles.counts().spread_rays >= spread);
  CHECK(one_point.counts().spread_rays == 0);
  CHECK(quartiles.counts().head_rows >= 4 * spread);
  CHECK(one_point.counts().head_rows < quartiles.counts().head_rows);
  // The quadrature over the quartiles is close to the dense sum, and closer than one point.
  INFO("mean |error| quartiles " << err_q / double(hits) << ", one point " << err_o / double(hits));
  CHECK(err_q / double(hits) < 0.01);
  CHECK(err_q <= err_o);
}

TEST_CASE("baked renderer: the run's evaluation rules, median and mix depth, from the caster's statistics",
          "[pipeline][bake]") {
  const SlabView sv;
  const Scene& view = sv.view;
  const bake::BakedScene& slab = sv.slab;
  const Pose& T = sv.T;
  const size_t n = sv.n;
  const std::vector<float>& cast = sv.cast;
  constexpr size_t K = bake::RayCaster::kOutputs;
  render::RenderConfig rules;
  BakedRenderer expected(test::runtime(), slab, rules);  // the vertex head
  DepthStats st;
  const RangeImage e = expected.render(T, view, &st);
  rules.eval_depth = "median";
  const RangeImage m = BakedRenderer(test::runtime(), slab, rules).render(T, view);
  rules.eval_depth = "mix";
  rules.eval_mix_factor = 1.0f;  // the rays above the frame's median variance
  const RangeImage x = BakedRenderer(test::runtime(), slab, rules).render(T, view);
  const double thr = mix_variance_threshold(st.variance_m2, 1.0);
  long hits = 0, mixed = 0;
  for (size_t p = 0; p < n; ++p) {
    CHECK(e.range[p] == cast[K * p]);
    CHECK(st.median_m[p] == cast[K * p + 8]);
    CHECK(st.variance_m2[p] == cast[K * p + 9]);
    CHECK(m.range[p] == cast[K * p + 8]);
    const bool wide = double(st.variance_m2[p]) > thr;
    CHECK(x.range[p] == (wide ? cast[K * p + 8] : cast[K * p]));
    CHECK(m.ray_drop[p] == e.ray_drop[p]);  // the rules move the range only
    hits += cast[K * p + 3] > 0.5f;
    mixed += wide;
  }
  REQUIRE(hits > 0);
  CHECK(mixed > 0);
  // On the slab the median lies where T = 1/2: ln 2 / 0.35 m behind the entry (within a lattice
  // step and the slab's 0.2 m voxels), the variance of an exponential cut at the slab's end.
  long along = 0;
  for (size_t p = 0; p < n; ++p) {
    const float* d = &view.directions[3 * p];
    if (!(cast[K * p + 3] > 0.9f) || d[0] < 0.99f || std::abs(d[1]) > 0.05f || std::abs(d[2]) > 0.05f)
      continue;
    ++along;
    CHECK(cast[K * p + 8] == Approx(4.0f / d[0] + std::log(2.0f) / 0.35f).margin(0.25f));
    CHECK(cast[K * p + 9] > 2.0f);  // metres of spread (1/σ² = 8.2 m² uncut)
  }
  CHECK(along > 0);
}
