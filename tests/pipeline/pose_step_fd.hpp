// The gradient of one whole training step's loss with respect to the pose correction ξ of the
// step's frame: analytic (the model's ray gradients through render::pose_gradient, and their
// sums on the device through render::pose_gradient_from_world_sums) and central finite
// differences, with the checks both pose-free FD tests apply (each component within 5 %
// of the largest, cosine > 0.98). Shared by test_pose_free.cpp (hash grid) and test_sgnlf.cpp
// (hybrid field).
#pragma once
#include <catch2/catch.hpp>

#include <cmath>

#include "pipeline/model/model.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "render/pose_gradient.hpp"

namespace sgnlf::test {

struct PoseStepGradients {
  Vec6 analytic, numeric;
  // The same analytic gradient from the ray gradients' sums on the device (the device profile's
  // pose_grad: device path: LidarNerfModel::read_ray_grad_sums,
  // render::pose_gradient_from_world_sums), available under any profile.
  Vec6 analytic_device;
};

// Batch of (seed 7, `step`); the frame's pose is its scene pose corrected by xi0 (and ± eps).
inline PoseStepGradients pose_step_gradients(pipeline::LidarNerfModel& model,
                                             const pipeline::Scene& scene,
                                             const pipeline::TrainConfig& c, long step,
                                             const Vec6& xi0, double eps) {
  const int frame = pipeline::batch_frame(scene, 7, step);
  const Pose& T_init = scene.T_world_lidar[size_t(frame)];
  auto loss_at = [&](const Vec6& xi) {
    const Pose T = corrected_pose(T_init, xi);
    const pipeline::RayBatch b = pipeline::draw_ray_batch(scene, c, 7, step, [&](int) { return T; });
    model.forward_backward(b, 7, step, true);
    return double(model.read_losses().total());
  };
  PoseStepGradients g;
  REQUIRE(std::isfinite(loss_at(xi0)));
  const auto rg = model.read_ray_grads();
  const pipeline::RayBatch b = pipeline::draw_ray_batch(scene, c, 7, step);
  std::vector<float> dirs;
  for (int px : b.pixels)
    for (int a = 0; a < 3; ++a) dirs.push_back(scene.directions[3 * size_t(px) + a]);
  g.analytic = render::pose_gradient(T_init, xi0, {}, dirs, rg.origin, rg.direction);
  const render::RayGradSums sums = model.read_ray_grad_sums();
  g.analytic_device = render::pose_gradient_from_world_sums(T_init, xi0, sums.origin, sums.cross);
  for (int k = 0; k < 6; ++k) {
    Vec6 xp = xi0, xm = xi0;
    xp[k] += eps;
    xm[k] -= eps;
    g.numeric[k] = (loss_at(xp) - loss_at(xm)) / (2 * eps);
  }
  return g;
}

inline void check_pose_step_gradients(const PoseStepGradients& g) {
  INFO("analytic " << g.analytic.transpose() << "\nnumeric  " << g.numeric.transpose()
                   << "\ndevice   " << g.analytic_device.transpose());
  const double scale = g.numeric.cwiseAbs().maxCoeff();
  REQUIRE(scale > 1e-3);
  for (int k = 0; k < 6; ++k) CHECK(std::abs(g.analytic[k] - g.numeric[k]) < 0.05 * scale);
  CHECK(g.analytic.dot(g.numeric) > 0.98 * g.analytic.norm() * g.numeric.norm());
  for (int k = 0; k < 6; ++k) CHECK(std::abs(g.analytic_device[k] - g.numeric[k]) < 0.05 * scale);
  // Device sums in float against the host's in double over the same float ray gradients.
  CHECK((g.analytic_device - g.analytic).norm() <= 1e-4 * g.analytic.norm());
}

}  // namespace sgnlf::test
