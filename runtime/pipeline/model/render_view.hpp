// Rendering full range images from a trained model at any pose (in chunks of rays), in metres:
// range = rendered depth / scale, intensity, ray_drop = predicted return probability (the
// metrics apply the > 0.5 mask, protocol §1/§4).
#pragma once
#include "pipeline/model/model.hpp"
#include "pipeline/model/scene.hpp"
#include "render/fast_render_config.hpp"
#include "render/occupancy_grid.hpp"

namespace sgnlf::pipeline {

// `T_world_lidar` in metres (dataset frame); chunk = rays per device call (≤ model capacity).
// A model with a time (LiDAR4D's 4D field) renders at dataset frame `frame`'s time; with
// frame < 0, at the time of the frame whose pose is nearest to T_world_lidar (nearest_frame).
// With `fast` (grid and config), the chunks go through model.render_rays_fast; the grid must
// have been built at the same frame's time for a 4D field (pipeline::FastRenderer does that).
struct FastView {
  const render::OccupancyGrid* grid = nullptr;
  const render::FastRenderConfig* cfg = nullptr;
  long evaluated = 0, head_rows = 0;  // density and head rows, added up over the chunks
  GridMarch::Rows march{};            // layout "march": the density rows by kind, added up
};
// With `stats` (protocol renderer only), per pixel the median depth (metres), the opacity Σ w
// and the weight-normalised depth variance (m²) of the same render (model.depth_stats()).
struct DepthStats {
  std::vector<float> median_m, opacity, variance_m2;
};
RangeImage render_view(LidarNerfModel& model, const Scene& scene, const Pose& T_world_lidar,
                       int chunk_rays, int frame = -1, FastView* fast = nullptr,
                       DepthStats* stats = nullptr);

// The dataset frame whose scene pose lies nearest to `T_world_lidar` (metres).
int nearest_frame(const Scene& scene, const Pose& T_world_lidar);

// The prediction as the metrics see it: range and intensity multiplied by (prob > 0.5).
RangeImage masked_prediction(const RangeImage& pred);

}  // namespace sgnlf::pipeline
