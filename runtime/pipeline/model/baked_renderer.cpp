// BakedRenderer (see baked_renderer.hpp).
#include "pipeline/model/baked_renderer.hpp"

#include <algorithm>
#include <chrono>

#include "core/error.hpp"

namespace sgnlf::pipeline {

BakedRenderer::BakedRenderer(cl::Runtime& rt, const bake::BakedScene& scene,
                             LidarNerfModel* field_head)
    : rt_(rt), scene_(scene), caster_(rt, scene), model_(field_head) {
  if (model_ && model_->temporal())
    throw ConfigError("baked renderer: the field head needs a static field");
}

RangeImage BakedRenderer::render(const Pose& T_world_lidar, const Scene& view,
                                 std::vector<float>* opacity) {
  const auto t0 = std::chrono::steady_clock::now();
  const int H = view.sensor.height, W = view.sensor.width;
  const size_t n = size_t(H) * size_t(W);
  if (n > cap_) {
    o_ = cl::Buffer(rt_, n * 12), d_ = cl::Buffer(rt_, n * 12), out_ = cl::Buffer(rt_, n * 16);
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
  const std::vector<float> out = out_.read_vec<float>(n * 4);
  RangeImage img(H, W);
  for (size_t p = 0; p < n; ++p) {
    img.range[p] = out[4 * p];
    img.ray_drop[p] = out[4 * p + 1];
    img.intensity[p] = out[4 * p + 2];
  }
  if (opacity) {
    opacity->resize(n);
    for (size_t p = 0; p < n; ++p) (*opacity)[p] = out[4 * p + 3];
  }
  if (model_) {
    // The head at each ray's surface point (normalised frame, clamped to the box as the
    // renderer clamps its samples) along the ray; rays that meet nothing keep zeros.
    const auto th = std::chrono::steady_clock::now();
    std::vector<size_t> rows;
    std::vector<float> x, dir;
    const double s = view.norm.scale;
    for (size_t p = 0; p < n; ++p) {
      const float opacity = out[4 * p + 3];
      if (!(opacity > 1e-4f)) continue;
      rows.push_back(p);
      const float t = out[4 * p] / opacity;
      for (size_t a = 0; a < 3; ++a) {
        const double xm = double(origins_[3 * p + a]) + double(dirs_[3 * p + a]) * t;
        x.push_back(std::clamp(float((xm - view.norm.center[long(a)]) * s), -1.0f, 1.0f));
        dir.push_back(dirs_[3 * p + a]);
      }
    }
    const std::vector<float> h = model_->head_at(x, dir, int(rows.size()));
    for (size_t q = 0; q < rows.size(); ++q) {
      const size_t p = rows[q];
      img.ray_drop[p] = out[4 * p + 3] * h[2 * q];
      img.intensity[p] = out[4 * p + 3] * h[2 * q + 1];
    }
    counts_.head_rows += long(rows.size());
    counts_.head_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - th).count();
  }
  counts_.render_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++counts_.frames;
  counts_.rays += long(n);
  return img;
}

}  // namespace sgnlf::pipeline
