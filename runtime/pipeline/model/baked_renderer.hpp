// The renderer of a baked scene (`sgnlf render --baked`, `eval --baked`; docs/baking.md): a view's
// rays (a Scene's sensor at T_world_lidar, world metres) cast against the scene by the OpenCL ray
// caster (bake::RayCaster), one launch per view, into a RangeImage as render_view returns one
// (range in metres, intensity, ray_drop = return probability). Counts rays and seconds for
// rays/s and frames/s.
// Two heads: "vertex" (the scene's own per-vertex return probability and intensity, baked along
// the nearest training origin's view: self-contained) or "field" (the trained model's LiDAR head
// with the ray's own direction, scaled by the ray's opacity: once per ray at its baked surface
// point o + d·depth/opacity where the weight lies within a voxel, at the weight's quartiles
// where it spreads; the head's view dependence kept, 1–4 field rows per ray instead of the
// field renderer's ~57; docs/baking.md).
#pragma once
#include <memory>
#include <vector>

#include "bake/baked_scene.hpp"
#include "bake/ray_caster.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/model/render_view.hpp"
#include "pipeline/model/scene.hpp"

namespace sgnlf::pipeline {

class BakedRenderer {
 public:
  // `field_head`: the model whose head runs per ray ("field"), or null ("vertex").
  // `head_spread_m`: with the field head, a ray whose weight's 1/8 and 7/8 quartiles lie further
  // apart takes a head row at each quartile, a ray within it one row (negative: the scene's
  // voxel; larger: fewer rows, faster, the far soft surfaces' probability and intensity taken at
  // one point; docs/baking.md measures both).
  // `rules`: the run's evaluation rules, applied to every view as render_view applies them
  // (render.eval_depth "median" or "mix" from the caster's median depth and variance,
  // render.eval_drop_out_of_range; pipeline/model/view_rules.hpp).
  BakedRenderer(cl::Runtime& rt, const bake::BakedScene& scene, const render::RenderConfig& rules,
                LidarNerfModel* field_head = nullptr, float head_spread_m = -1.0f);

  // The view of `view`'s sensor at T_world_lidar (metres, the dataset's world frame); with
  // `stats`, each pixel's median depth, opacity Σw and depth variance (row-major, as the image).
  RangeImage render(const Pose& T_world_lidar, const Scene& view, DepthStats* stats = nullptr);

  struct Counts {
    long frames = 0, rays = 0;
    double render_seconds = 0.0;  // ray setup, cast and read-back, per view (head included)
    double head_seconds = 0.0;    // "field": the head rows
    long head_rows = 0;
    long spread_rays = 0;  // "field": rays whose weight spreads over more than a voxel
  };
  const Counts& counts() const { return counts_; }
  const bake::BakedScene& scene() const { return scene_; }
  const char* head() const { return model_ ? "field" : "vertex"; }

 private:
  cl::Runtime& rt_;
  const bake::BakedScene& scene_;
  bake::RayCaster caster_;
  render::RenderConfig rules_;
  LidarNerfModel* model_;
  float spread_m_;
  cl::Buffer o_, d_, out_;
  size_t cap_ = 0;
  std::vector<float> origins_, dirs_;
  Counts counts_;
};

}  // namespace sgnlf::pipeline
