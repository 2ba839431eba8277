// Ray batches for training (method.md §1, LiDAR-NeRF's loader): each iteration draws its rays
// from one training frame; frames are visited in a fresh Philox permutation every epoch
// (epoch = one pass over the training frames). On even epochs, when the gradient loss is on,
// the batch is made of patch_rows × patch_cols pixel patches (row-major inside a patch,
// patches concatenated: render::RangeLoss::patch_gradient's layout) for the range-image
// gradient loss; otherwise pixels are drawn uniformly over the H×W image (with replacement). Everything is keyed by (seed, step):
// the batch of a step does not depend on what was drawn before, so resume is exact.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "pipeline/model/scene.hpp"
#include "pipeline/config/train_config.hpp"

namespace sgnlf::pipeline {

struct RayBatch {
  int frame = 0;            // index into the dataset's frames
  bool patches = false;     // patch layout (gradient loss applies)
  int n_rays = 0;
  std::vector<int> pixels;  // row-major pixel index per ray
  std::vector<float> origins, directions;  // n_rays × 3, normalised world frame
  std::vector<float> range, intensity, label;  // ground truth per ray (range normalised)
};

// Frame visited at `step` (a permutation of scene.train per epoch).
int batch_frame(const Scene& scene, uint64_t seed, long step);
bool batch_uses_patches(const Scene& scene, const TrainConfig& c, long step);
// Rays start from `pose_of(frame)` (normalised frame) when given (the current estimate of a
// pose-free run), else from scene.T_world_lidar.
RayBatch draw_ray_batch(const Scene& scene, const TrainConfig& c, uint64_t seed, long step,
                        const std::function<Pose(int)>& pose_of = {});

// Rays of a whole range image of `frame_pose` (normalised frame), pixels [begin, end).
void image_rays(const Scene& scene, const Pose& T_world_lidar, size_t begin, size_t end,
                std::vector<float>& origins, std::vector<float>& directions);

}  // namespace sgnlf::pipeline
