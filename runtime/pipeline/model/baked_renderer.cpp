// BakedRenderer (see baked_renderer.hpp).
#include "pipeline/model/baked_renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "bake/head_rows.hpp"
#include "core/error.hpp"
#include "pipeline/model/view_rules.hpp"

namespace sgnlf::pipeline {

BakedRenderer::BakedRenderer(cl::Runtime& rt, const bake::BakedScene& scene,
                             const render::RenderConfig& rules, LidarNerfModel* field_head,
                             float head_spread_m)
    : rt_(rt), scene_(scene), caster_(rt, scene), rules_(rules), model_(field_head),
      spread_m_(head_spread_m < 0.0f ? scene.voxel_m : head_spread_m) {
  if (model_ && model_->temporal())
    throw ConfigError("baked renderer: the field head needs a static field");
  if (!std::isfinite(spread_m_))
    throw ConfigError("baked renderer: head spread " + std::to_string(head_spread_m) +
                      " m is not a finite length");
}

RangeImage BakedRenderer::render(const Pose& T_world_lidar, const Scene& view,
                                 DepthStats* stats) {
  const auto t0 = std::chrono::steady_clock::now();
  const int H = view.sensor.height, W = view.sensor.width;
  const size_t n = size_t(H) * size_t(W);
  if (n > cap_) {
    o_ = cl::Buffer(rt_, n * 12), d_ = cl::Buffer(rt_, n * 12),
    out_ = cl::Buffer(rt_, n * bake::RayCaster::kOutputs * sizeof(float));
    cap_ = n;
  }
  // World rays: the sensor's directions rotated, every ray from the sensor's origin (metres).
  const Eigen::Matrix3f R = T_world_lidar.rotation().cast<float>();
  const Eigen::Vector3f t = T_world_lidar.translation().cast<float>();
  origins_.resize(n * 3), dirs_.resize(n * 3);
  for (size_t p = 0; p < n; ++p) {
    const Eigen::Vector3f d =
        R * Eigen::Vector3f(view.directions[3 * p], view.directions[3 * p + 1], view.directions[3 * p + 2]);
    for (int a = 0; a < 3; ++a) origins_[3 * p + size_t(a)] = t[a], dirs_[3 * p + size_t(a)] = d[a];
  }
  o_.write_vec(origins_);
  d_.write_vec(dirs_);
  caster_.cast(o_, d_, int(n), out_);
  constexpr size_t K = bake::RayCaster::kOutputs;
  const std::vector<float> out = out_.read_vec<float>(n * K);
  RangeImage img(H, W);
  for (size_t p = 0; p < n; ++p) {
    img.range[p] = out[K * p];
    img.ray_drop[p] = out[K * p + 1];
    img.intensity[p] = out[K * p + 2];
  }
  // The evaluation's depth statistics, as render_view's (median, opacity, variance).
  const bool mix = rules_.eval_depth == "mix", median = rules_.eval_depth == "median";
  DepthStats own;
  if (mix && !stats) stats = &own;
  if (stats) {
    stats->median_m.resize(n), stats->opacity.resize(n), stats->variance_m2.resize(n);
    for (size_t p = 0; p < n; ++p) {
      stats->median_m[p] = out[K * p + 8];
      stats->opacity[p] = out[K * p + 3];
      stats->variance_m2[p] = out[K * p + 9];
    }
  }
  if (model_) {
    // The head where each ray's weight lies (bake::head_rows: one row at the surface point, or
    // one at each quartile where the weight spreads), in the normalised frame, clamped to the
    // box as the renderer clamps its samples, with the ray's direction: Σ w·head as the field's
    // renderer sums it, by quadrature over the weight. Rays that meet nothing keep zeros.
    const auto th = std::chrono::steady_clock::now();
    const std::vector<bake::HeadRow> rows = bake::head_rows(out, n, spread_m_, &counts_.spread_rays);
    std::vector<float> x, dir;
    x.reserve(rows.size() * 3), dir.reserve(rows.size() * 3);
    const double s = view.norm.scale;
    for (const auto& row : rows)
      for (size_t a = 0; a < 3; ++a) {
        const size_t i = 3 * row.ray + a;
        const double xm = double(origins_[i]) + double(dirs_[i]) * row.t_m;
        x.push_back(std::clamp(float((xm - view.norm.center[long(a)]) * s), -1.0f, 1.0f));
        dir.push_back(dirs_[i]);
      }
    const std::vector<float> h = model_->head_at(x, dir, int(rows.size()));
    for (size_t p = 0; p < n; ++p)
      if (out[K * p + 3] > 1e-4f) img.ray_drop[p] = img.intensity[p] = 0.0f;
    for (size_t q = 0; q < rows.size(); ++q) {
      const size_t p = rows[q].ray;
      img.ray_drop[p] += rows[q].weight * h[2 * q];
      img.intensity[p] += rows[q].weight * h[2 * q + 1];
    }
    counts_.head_rows += long(rows.size());
    counts_.head_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - th).count();
  }
  // The run's evaluation rules, in render_view's order (the head took the expected depth's
  // surface point: the rules choose the reported range only).
  if (median)
    for (size_t p = 0; p < n; ++p) img.range[p] = out[K * p + 8];
  if (mix) apply_mix_depth(img, *stats, double(rules_.eval_mix_factor));
  if (rules_.eval_drop_out_of_range) drop_out_of_range(img, view.sensor);
  counts_.render_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++counts_.frames;
  counts_.rays += long(n);
  return img;
}

}  // namespace sgnlf::pipeline
