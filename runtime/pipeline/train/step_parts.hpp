// The step parts of a training run (methods/method.hpp's StepParts) built on the device: a
// method's compose() asks for them, in its order, and this object owns what it built (the loss
// terms a part adds, the model's list owns). Each part is built only when the config turns its
// feature on (TrainConfig::confidence_graph(), consistency_term(), hybrid_encoder(),
// flow_supervision()), else it hands back the policy it was given.
#pragma once
#include <memory>
#include <string>

#include "cl/runtime.hpp"
#include "datasets/dataset.hpp"
#include "pipeline/train/consistency_schedule.hpp"
#include "pipeline/train/flow_supervision.hpp"
#include "pipeline/methods/method.hpp"
#include "pipeline/train/pose_free_step.hpp"
#include "pipeline/train/spectral_schedule.hpp"

namespace sgnlf::pipeline {

class RunStepParts : public StepParts {
 public:
  RunStepParts(cl::Runtime& rt, const Dataset& d, const Scene& scene, const TrainConfig& c,
               LidarNerfModel& model, std::string run_dir, uint64_t seed);

  StepPolicy& ground_truth_poses() override;
  StepPolicy& pose_free() override;
  StepPolicy& consistency(StepPolicy& inner) override;
  StepPolicy& spectral(StepPolicy& inner) override;
  StepPolicy& scene_flow(StepPolicy& inner) override;

  // What was built (null when not).
  PoseFreeStep* pose_step() { return pose_step_.get(); }
  ConsistencySchedule* consistency_step() { return consistency_step_.get(); }
  SpectralSchedule* spectral_step() { return spectral_step_.get(); }
  FlowSupervision* flow_term() { return flow_; }

 private:
  cl::Runtime& rt_;
  const Dataset& d_;
  const Scene& scene_;
  const TrainConfig& c_;
  LidarNerfModel& model_;
  std::string run_dir_;
  uint64_t seed_;
  std::unique_ptr<GroundTruthPoseStep> gt_step_;
  std::unique_ptr<PoseSet> poses_;
  std::unique_ptr<PoseFreeStep> pose_step_;
  std::unique_ptr<ConsistencySchedule> consistency_step_;
  std::unique_ptr<SpectralSchedule> spectral_step_;
  FlowSupervision* flow_ = nullptr;  // owned by the model's list of loss terms
};

}  // namespace sgnlf::pipeline
