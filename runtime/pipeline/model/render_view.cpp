// render_view: chunked full-image rendering (see render_view.hpp).
#include "pipeline/model/render_view.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "pipeline/model/view_rules.hpp"

namespace sgnlf::pipeline {

int nearest_frame(const Scene& scene, const Pose& T_world_lidar) {
  const Pose T = normalize_pose(T_world_lidar, scene.norm);
  int best = 0;
  double best_d = -1.0;
  for (size_t k = 0; k < scene.T_world_lidar.size(); ++k) {
    const double d = (scene.T_world_lidar[k].translation() - T.translation()).squaredNorm();
    if (best_d < 0.0 || d < best_d) best = int(k), best_d = d;
  }
  return best;
}

RangeImage render_view(LidarNerfModel& model, const Scene& scene, const Pose& T_world_lidar,
                       int chunk_rays, int frame, FastView* fast, DepthStats* stats) {
  const int H = scene.sensor.height, W = scene.sensor.width;
  RangeImage img(H, W);
  const Pose T = normalize_pose(T_world_lidar, scene.norm);
  if (model.temporal())
    model.set_frame(frame >= 0 ? frame : nearest_frame(scene, T_world_lidar),
                    int(scene.T_world_lidar.size()));
  const size_t n = img.size();
  require(!(fast && stats), "render_view: depth statistics come from the protocol renderer only");
  const render::RenderConfig& rc = model.render_config();
  // "mix" is the protocol renderer's (the fast one renders the median depth for it).
  const bool mix = rc.eval_depth == "mix" && !fast;
  DepthStats own;
  if (mix && !stats) stats = &own;
  if (stats) {
    stats->median_m.assign(n, 0.0f);
    stats->opacity.assign(n, 0.0f);
    stats->variance_m2.assign(n, 0.0f);
  }
  std::vector<float> o, d;
  for (size_t begin = 0; begin < n; begin += size_t(chunk_rays)) {
    const size_t end = std::min(n, begin + size_t(chunk_rays));
    image_rays(scene, T, begin, end, o, d);
    const auto out = fast ? model.render_rays_fast(o, d, int(end - begin), *fast->grid, *fast->cfg)
                          : model.render_rays(o, d, int(end - begin));
    if (fast) {
      fast->evaluated += model.fast_evaluated(), fast->head_rows += model.fast_head_rows();
      const GridMarch::Rows& k = model.march_rows();
      fast->march.coarse += k.coarse, fast->march.fine += k.fine;
      fast->march.outside += k.outside, fast->march.dropped += k.dropped;
    }
    for (size_t p = begin; p < end; ++p) {
      const float* v = &out[3 * (p - begin)];
      img.range[p] = float(double(v[0]) / scene.norm.scale);
      img.intensity[p] = v[2];
      img.ray_drop[p] = v[1];
    }
    if (stats) {
      const auto st = model.depth_stats();
      const double s = scene.norm.scale;
      for (size_t p = begin; p < end; ++p) {
        const float* v = &st[3 * (p - begin)];
        stats->median_m[p] = float(double(v[0]) / s);
        stats->opacity[p] = v[1];
        stats->variance_m2[p] = float(double(v[2]) / (s * s));
      }
    }
  }
  if (mix) apply_mix_depth(img, *stats, double(rc.eval_mix_factor));
  if (rc.eval_drop_out_of_range) drop_out_of_range(img, scene.sensor);
  return img;
}

RangeImage masked_prediction(const RangeImage& pred) {
  RangeImage m = pred;
  for (size_t p = 0; p < m.size(); ++p) {
    const float mask = pred.ray_drop[p] > 0.5f ? 1.0f : 0.0f;
    m.range[p] *= mask;
    m.intensity[p] *= mask;
    m.ray_drop[p] = mask;
  }
  return m;
}

}  // namespace sgnlf::pipeline
