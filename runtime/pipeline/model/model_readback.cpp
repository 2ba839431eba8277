// LidarNerfModel's read-backs (model.hpp): what the host reads of a pass, the loss terms' values,
// the ray gradients (whole, or summed on the device for the pose gradient), the live counts and
// the output gradient. The loss buffer is read once for every term; with the ray-gradient sums
// it comes back in one read (read_losses_and_ray_grad_sums), under the gpu profile the pose-free
// step's only blocking transfer (tests/pipeline/test_step_parallelism.cpp).
#include <algorithm>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/model/model_detail.hpp"

namespace sgnlf::pipeline {
using namespace model_detail;

RayGrads LidarNerfModel::read_ray_grads() const {
  if (grad_rays_ == 0) throw Error("LidarNerfModel::read_ray_grads: no step computed ray gradients");
  RayGrads g;
  const size_t n = size_t(grad_rays_) * 3;
  g.origin = g_o_.read_vec<float>(n);
  g.direction = g_d_.read_vec<float>(n);
  const auto dir_enc = g_dir_.read_vec<float>(n);
  for (size_t i = 0; i < n; ++i) g.direction[i] += dir_enc[i];
  return g;
}

render::RayGradSums LidarNerfModel::read_ray_grad_sums() {
  if (grad_rays_ == 0)
    throw Error("LidarNerfModel::read_ray_grad_sums: no step computed ray gradients");
  if (!pose_sums_) pose_sums_ = std::make_unique<render::PoseGradSums>(rt_);
  // d_ still holds the directions of the pass whose ray gradients these are.
  pose_sums_->reduce(grad_rays_, d_, g_o_, g_d_, g_dir_);
  return pose_sums_->read();
}

LidarNerfModel::LossAndRaySums LidarNerfModel::read_losses_and_ray_grad_sums() {
  if (grad_rays_ == 0)
    throw Error("LidarNerfModel::read_losses_and_ray_grad_sums: no step computed ray gradients");
  if (!pose_sums_) pose_sums_ = std::make_unique<render::PoseGradSums>(rt_);
  if (!loss_and_sums_) loss_and_sums_ = floats(rt_, kLossBufferFloats + 6);
  pose_sums_->reduce(grad_rays_, d_, g_o_, g_d_, g_dir_);
  const size_t loss_bytes = kLossBufferFloats * sizeof(float);
  loss_and_sums_.copy_from(loss_buf_, loss_bytes);
  loss_and_sums_.copy_from(pose_sums_->sums(), 6 * sizeof(float), 0, loss_bytes);
  const std::vector<float> all = loss_and_sums_.read_vec<float>(kLossBufferFloats + 6);
  LossAndRaySums r;
  const std::vector<float> loss(all.begin(), all.begin() + long(kLossBufferFloats));
  losses_.each([&](const LossTerm& t) { t.report(r.loss, loss); });
  r.sums = render::PoseGradSums::from_floats(all.data() + kLossBufferFloats);
  return r;
}

LossReport LidarNerfModel::read_losses() const {
  const std::vector<float> loss = loss_buf_.read_vec<float>(kLossBufferFloats);
  LossReport r;
  losses_.each([&](const LossTerm& t) { t.report(r, loss); });
  return r;
}

std::vector<int> LidarNerfModel::live_counts() const {
  if (!last_.samples.compacted || last_.pass != pass_)
    throw Error("LidarNerfModel::live_counts: the last pass did not terminate rays early");
  return live_->counts(last_.samples.n_rays);
}

std::vector<float> LidarNerfModel::read_output_gradient() const {
  return grad_out_.read_vec<float>(size_t(std::max(1, last_.samples.n_rays)) * 3);
}

}  // namespace sgnlf::pipeline
