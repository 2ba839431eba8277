// The fast renderer of a trained field (`sgnlf render`'s default; the tables keep the protocol's
// renderer, render_view without it): the field's occupancy grid over the box of the scene's
// training points, their cells occupied too (render::OccupancyGrid, built on first use; for a 4D field one grid per frame
// time, built when that time is first rendered) and render_view through
// LidarNerfModel::render_rays_fast. Counts what it did for rays/s and frames/s.
#pragma once
#include <map>
#include <memory>

#include "pipeline/model/render_view.hpp"
#include "render/fast_render_config.hpp"
#include "render/occupancy_grid.hpp"

namespace sgnlf::pipeline {

// The scene's training frames' returns (range > 0) under its poses, n × 3 in the normalised
// frame (NumericError when there are none), and their box.
std::vector<float> scene_points(const Scene& scene);
render::GridBox points_box(const std::vector<float>& points);

class FastRenderer {
 public:
  FastRenderer(cl::Runtime& rt, LidarNerfModel& model, const Scene& scene,
               const render::FastRenderConfig& cfg, int chunk_rays);

  // As render_view (frame < 0: the nearest dataset frame's time for a 4D field); `view` (from
  // view_with_sensor) renders another sensor's rays, the grid staying the scene's.
  RangeImage render(const Pose& T_world_lidar, int frame = -1, const Scene* view = nullptr);
  // The grid for dataset frame `frame` (any frame for a field without time), built on first use.
  const render::OccupancyGrid& grid(int frame);

  struct Counts {
    long frames = 0, rays = 0;
    long evaluated = 0, head_rows = 0;  // density and head rows, summed over chunks
    GridMarch::Rows march;              // layout "march": the density rows by kind
    double render_seconds = 0.0;        // render() wall time, grids excluded
    double grid_seconds = 0.0;          // grid builds
    int grids = 0;
  };
  const Counts& counts() const { return counts_; }
  const render::FastRenderConfig& config() const { return cfg_; }

 private:
  cl::Runtime& rt_;
  LidarNerfModel& model_;
  const Scene& scene_;
  render::FastRenderConfig cfg_;
  int chunk_;
  std::vector<float> points_;  // the training returns: their cells are occupied
  render::GridBox box_;
  std::map<int, std::unique_ptr<render::OccupancyGrid>> grids_;  // by frame (−1: no time)
  Counts counts_;
};

}  // namespace sgnlf::pipeline
