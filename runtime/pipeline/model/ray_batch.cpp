// Host Philox ray-batch drawing (see ray_batch.hpp). Streams: 1 = epoch permutations,
// 2 = pixel draws of a step.
#include "pipeline/model/ray_batch.hpp"

#include <numeric>

#include "core/rng.hpp"

namespace sgnlf::pipeline {
namespace {

constexpr uint32_t kStreamPermutation = 0x50524d31u;  // keyed further by the epoch
constexpr uint32_t kStreamPixels = 0x50495831u;

}  // namespace

int batch_frame(const Scene& scene, uint64_t seed, long step) {
  const long n = long(scene.train.size());
  const long epoch = step / n, k = step % n;
  std::vector<int> perm(scene.train);
  Rng rng(seed ^ (uint64_t(epoch) * 0x9E3779B97F4A7C15ull), kStreamPermutation);
  for (long i = n - 1; i > 0; --i) std::swap(perm[i], perm[rng.below(uint32_t(i + 1))]);
  return perm[k];
}

bool batch_uses_patches(const Scene& scene, const TrainConfig& c, long step) {
  if (c.render.weights.grad <= 0.0f) return false;
  const long epoch = step / long(scene.train.size());
  return !c.schedule.patches_on_even_epochs || epoch % 2 == 0;
}

void image_rays(const Scene& scene, const Pose& T, size_t begin, size_t end,
                std::vector<float>& o, std::vector<float>& d) {
  const Eigen::Matrix3f R = T.rotation().cast<float>();
  const Eigen::Vector3f t = T.translation().cast<float>();
  o.resize((end - begin) * 3);
  d.resize((end - begin) * 3);
  for (size_t p = begin; p < end; ++p) {
    const Eigen::Vector3f dir_s(scene.directions[3 * p], scene.directions[3 * p + 1],
                                scene.directions[3 * p + 2]);
    const Eigen::Vector3f dir_w = R * dir_s;
    for (int a = 0; a < 3; ++a) {
      o[3 * (p - begin) + a] = t[a];
      d[3 * (p - begin) + a] = dir_w[a];
    }
  }
}

RayBatch draw_ray_batch(const Scene& scene, const TrainConfig& c, uint64_t seed, long step,
                        const std::function<Pose(int)>& pose_of) {
  RayBatch b;
  b.frame = batch_frame(scene, seed, step);
  b.patches = batch_uses_patches(scene, c, step);
  b.n_rays = c.schedule.rays_per_batch;
  const int H = scene.sensor.height, W = scene.sensor.width;
  Rng rng(seed ^ (uint64_t(step) * 0xD1B54A32D192ED03ull), kStreamPixels);
  b.pixels.resize(size_t(b.n_rays));
  if (b.patches) {
    const int PR = c.render.patch_rows, PC = c.render.patch_cols;
    const int ph = std::min(PR, H), pw = std::min(PC, W);
    for (int p = 0; p < b.n_rays / (PR * PC); ++p) {
      const int r0 = int(rng.below(uint32_t(H - ph + 1))), c0 = int(rng.below(uint32_t(W - pw + 1)));
      for (int i = 0; i < PR * PC; ++i) {
        const int r = r0 + std::min(i / PC, ph - 1), col = c0 + std::min(i % PC, pw - 1);
        b.pixels[size_t(p) * PR * PC + size_t(i)] = r * W + col;
      }
    }
  } else {
    for (auto& px : b.pixels) px = int(rng.below(uint32_t(H * W)));
  }
  const Pose T = pose_of ? pose_of(b.frame) : scene.T_world_lidar[size_t(b.frame)];
  const RangeImage& img = scene.images[size_t(b.frame)];
  std::vector<float> o, d;
  b.origins.resize(size_t(b.n_rays) * 3);
  b.directions.resize(size_t(b.n_rays) * 3);
  b.range.resize(size_t(b.n_rays));
  b.intensity.resize(size_t(b.n_rays));
  b.label.resize(size_t(b.n_rays));
  for (int i = 0; i < b.n_rays; ++i) {
    const size_t p = size_t(b.pixels[size_t(i)]);
    image_rays(scene, T, p, p + 1, o, d);
    for (int a = 0; a < 3; ++a) {
      b.origins[3 * size_t(i) + a] = o[size_t(a)];
      b.directions[3 * size_t(i) + a] = d[size_t(a)];
    }
    b.range[size_t(i)] = img.range[p];
    b.intensity[size_t(i)] = img.intensity[p];
    b.label[size_t(i)] = img.ray_drop[p];
  }
  return b;
}

}  // namespace sgnlf::pipeline
