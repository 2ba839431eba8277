// RunStepParts (see step_parts.hpp).
#include "pipeline/train/step_parts.hpp"

#include "datasets/protocol.hpp"
#include "pipeline/train/geometric_stage.hpp"
#include "pipeline/model/model.hpp"

namespace sgnlf::pipeline {

RunStepParts::RunStepParts(cl::Runtime& rt, const Dataset& d, const Scene& scene,
                           const TrainConfig& c, LidarNerfModel& model, std::string run_dir,
                           uint64_t seed)
    : rt_(rt), d_(d), scene_(scene), c_(c), model_(model), run_dir_(std::move(run_dir)),
      seed_(seed) {}

StepPolicy& RunStepParts::ground_truth_poses() {
  gt_step_ = std::make_unique<GroundTruthPoseStep>(scene_, c_);
  return *gt_step_;
}

// The poses are parameters, and a geometric stage may run before epochs.
StepPolicy& RunStepParts::pose_free() {
  require(c_.is_pose_free(), "the pose-free step needs the config's pose-free sections");
  const PoseFreeConfig& pf = *c_.pose_free;
  poses_ = std::make_unique<PoseSet>(scene_.T_world_lidar, pf.pose_optim,
                                     pf.pose_optim.lr_scale(pf.poses.init));
  pose_step_ = std::make_unique<PoseFreeStep>(
      scene_, c_, *poses_, d_.has_reference_poses ? gt_poses(d_) : std::vector<Pose>{}, run_dir_,
      c_.confidence_graph()
          ? make_geometric_stage(d_, scene_, c_, field_features(model_, scene_.norm), run_dir_)
          : make_geometric_stage(d_, scene_, c_));
  pose_step_->set_pose_reference(d_.planar_reference ? metrics::PoseReference::horizontal
                                                     : metrics::PoseReference::full_3d);
  return *pose_step_;
}

StepPolicy& RunStepParts::consistency(StepPolicy& inner) {
  if (!c_.consistency_term()) return inner;
  require(poses_ != nullptr, "the cross-frame consistency needs a pose-free method");
  // The term runs in the model's step; the schedule logs it and checkpoints its state.
  auto& loss = static_cast<ConsistencyLoss&>(model_.add_loss(std::make_unique<ConsistencyLoss>(
      rt_, scene_, c_, *poses_, model_capacity(c_), seed_)));
  consistency_step_ = std::make_unique<ConsistencySchedule>(inner, loss);
  return *consistency_step_;
}

// Ψ trains in the model's step (a loss term with its own parameter group); the schedule sets
// λ(t), rebuilds the surface pool each epoch and checkpoints Ψ.
StepPolicy& RunStepParts::spectral(StepPolicy& inner) {
  if (!c_.hybrid_encoder()) return inner;
  require(poses_ != nullptr, "the hybrid spectral field needs a pose-free method");
  const PoseSet& ps = *poses_;
  auto& loss = static_cast<SpectralLoss&>(model_.add_loss(std::make_unique<SpectralLoss>(
      rt_, model_.psi_params(), c_,
      make_surface_pool_source(d_, scene_, c_.spectral->points_per_frame, seed_), seed_)));
  spectral_step_ = std::make_unique<SpectralSchedule>(
      inner, loss, model_, c_, [&ps](int frame) { return ps.pose(size_t(frame)); });
  return *spectral_step_;
}

StepPolicy& RunStepParts::scene_flow(StepPolicy& inner) {
  if (!c_.flow_supervision()) return inner;
  require(model_.temporal(), "the scene-flow supervision needs the 4D encoder (config 'lidar4d')");
  // A loss term of the model's step: `inner` is the step.
  flow_ = &static_cast<FlowSupervision&>(model_.add_loss(
      make_flow_supervision(rt_.device_profile().chamfer, d_, scene_, c_, seed_)));
  return inner;
}

}  // namespace sgnlf::pipeline
