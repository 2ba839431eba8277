// BakedRenderer (see baked_renderer.hpp).
#include "pipeline/model/baked_renderer.hpp"

#include <chrono>

namespace sgnlf::pipeline {

BakedRenderer::BakedRenderer(cl::Runtime& rt, const bake::BakedScene& scene)
    : rt_(rt), scene_(scene), caster_(rt, scene) {}

RangeImage BakedRenderer::render(const Pose& T_world_lidar, const Scene& view) {
  const auto t0 = std::chrono::steady_clock::now();
  const int H = view.sensor.height, W = view.sensor.width;
  const size_t n = size_t(H) * size_t(W);
  if (n > cap_) {
    o_ = cl::Buffer(rt_, n * 12), d_ = cl::Buffer(rt_, n * 12), out_ = cl::Buffer(rt_, n * 12);
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
  const std::vector<float> out = out_.read_vec<float>(n * 3);
  RangeImage img(H, W);
  for (size_t p = 0; p < n; ++p) {
    img.range[p] = out[3 * p];
    img.ray_drop[p] = out[3 * p + 1];
    img.intensity[p] = out[3 * p + 2];
  }
  counts_.render_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++counts_.frames;
  counts_.rays += long(n);
  return img;
}

}  // namespace sgnlf::pipeline
