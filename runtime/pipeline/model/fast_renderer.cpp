// FastRenderer (see fast_renderer.hpp).
#include "pipeline/model/fast_renderer.hpp"

#include <algorithm>
#include <chrono>
#include <limits>

#include "core/error.hpp"
#include "core/log.hpp"

namespace sgnlf::pipeline {

std::vector<float> scene_points(const Scene& scene) {
  std::vector<float> pts;
  for (int k : scene.train) {
    const RangeImage& img = scene.images[size_t(k)];
    const Pose& T = scene.T_world_lidar[size_t(k)];
    for (size_t p = 0; p < img.size(); ++p) {
      const float r = img.range[p];
      if (!(r > 0.0f)) continue;
      const Eigen::Vector3d dir(scene.directions[3 * p], scene.directions[3 * p + 1],
                                scene.directions[3 * p + 2]);
      const Eigen::Vector3d w = T * (dir * double(r));
      for (int a = 0; a < 3; ++a) pts.push_back(float(w[a]));
    }
  }
  if (pts.empty()) throw NumericError("scene_points: the training frames have no returns");
  return pts;
}

render::GridBox points_box(const std::vector<float>& pts) {
  render::GridBox b;
  for (size_t a = 0; a < 3; ++a) b.lo[a] = std::numeric_limits<float>::max(), b.hi[a] = -b.lo[a];
  for (size_t p = 0; p + 2 < pts.size(); p += 3)
    for (size_t a = 0; a < 3; ++a)
      b.lo[a] = std::min(b.lo[a], pts[p + a]), b.hi[a] = std::max(b.hi[a], pts[p + a]);
  return b;
}

FastRenderer::FastRenderer(cl::Runtime& rt, LidarNerfModel& model, const Scene& scene,
                           const render::FastRenderConfig& cfg, int chunk_rays)
    : rt_(rt), model_(model), scene_(scene), cfg_(cfg), chunk_(chunk_rays),
      points_(scene_points(scene)), box_(points_box(points_)) {
  cfg_.validate();
  if (model_.render_config().eval_depth == "mix")
    log::info("fast renderer: render.eval_depth \"mix\" needs the protocol renderer's depth "
              "variance; the fast renderer renders the median depth on every ray (--renderer "
              "protocol for mix)");
}

const render::OccupancyGrid& FastRenderer::grid(int frame) {
  const int key = model_.temporal() ? frame : -1;
  auto it = grids_.find(key);
  if (it != grids_.end()) return *it->second;
  if (model_.temporal()) model_.set_frame(frame, int(scene_.T_world_lidar.size()));
  auto g = std::make_unique<render::OccupancyGrid>(render::OccupancyGrid::build(
      rt_, cfg_, box_, float(scene_.norm.scale), model_.bin_width(),
      [&](const std::vector<float>& x, int n) { return model_.density_logits(x, n); },
      model_.sample_capacity(), points_));
  counts_.grid_seconds += g->build_seconds;
  ++counts_.grids;
  const auto d = g->dims();
  log::info("fast renderer: occupancy grid ", d[0], " x ", d[1], " x ", d[2], " cells of ",
            cfg_.cell_m, " m, ", 100.0 * g->occupied_fraction(), " % occupied, built in ",
            g->build_seconds, " s");
  return *grids_.emplace(key, std::move(g)).first->second;
}

RangeImage FastRenderer::render(const Pose& T_world_lidar, int frame, const Scene* view) {
  if (model_.temporal() && frame < 0) frame = nearest_frame(scene_, T_world_lidar);
  const render::OccupancyGrid& g = grid(frame);
  const auto t0 = std::chrono::steady_clock::now();
  FastView fast{&g, &cfg_};
  const Scene& v = view ? *view : scene_;
  RangeImage img = render_view(model_, v, T_world_lidar, chunk_, frame, &fast);
  counts_.render_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++counts_.frames;
  counts_.evaluated += fast.evaluated;
  counts_.head_rows += fast.head_rows;
  counts_.march.coarse += fast.march.coarse, counts_.march.fine += fast.march.fine;
  counts_.march.outside += fast.march.outside, counts_.march.dropped += fast.march.dropped;
  counts_.rays += long(img.size());
  return img;
}

}  // namespace sgnlf::pipeline
