// The pose gradient's two strategies (pose_grad_reader.hpp).
#include "pipeline/train/pose_grad_reader.hpp"

#include <optional>

#include "render/pose_gradient.hpp"

namespace sgnlf::pipeline {
namespace {

class HostPoseGrad final : public PoseGradReader {
 public:
  LossReport read_losses(LidarNerfModel& model, bool) override { return model.read_losses(); }
  Vec6 pose_gradient(LidarNerfModel& model, const Scene& scene, const PoseSet& poses,
                     const RayBatch& b) override {
    const size_t f = size_t(b.frame);
    const RayGrads g = model.read_ray_grads();
    std::vector<float> dirs_lidar(size_t(b.n_rays) * 3);
    for (int i = 0; i < b.n_rays; ++i)
      for (int a = 0; a < 3; ++a)
        dirs_lidar[3 * size_t(i) + a] = scene.directions[3 * size_t(b.pixels[size_t(i)]) + a];
    return render::pose_gradient(poses.initial(f), poses.correction(f), {}, dirs_lidar, g.origin,
                                 g.direction);
  }
};

class DevicePoseGrad final : public PoseGradReader {
 public:
  LossReport read_losses(LidarNerfModel& model, bool pose_follows) override {
    if (!pose_follows) return model.read_losses();
    LidarNerfModel::LossAndRaySums r = model.read_losses_and_ray_grad_sums();
    sums_ = r.sums;
    return std::move(r.loss);
  }
  Vec6 pose_gradient(LidarNerfModel& model, const Scene&, const PoseSet& poses,
                     const RayBatch& b) override {
    const size_t f = size_t(b.frame);
    const render::RayGradSums s = sums_ ? *sums_ : model.read_ray_grad_sums();
    sums_.reset();
    return render::pose_gradient_from_world_sums(poses.initial(f), poses.correction(f), s.origin,
                                                 s.cross);
  }

 private:
  std::optional<render::RayGradSums> sums_;  // read with the loss, for this step's gradient
};

}  // namespace

std::unique_ptr<PoseGradReader> make_pose_grad_reader(cl::PoseGrad where) {
  if (where == cl::PoseGrad::Device) return std::make_unique<DevicePoseGrad>();
  return std::make_unique<HostPoseGrad>();
}

}  // namespace sgnlf::pipeline
