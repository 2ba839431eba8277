// What one training iteration does, as the trainer's per-step and per-epoch hooks: the trainer
// (trainer.hpp) owns the loop, learning-rate schedule, logging, divergence checks and
// checkpoints; a StepPolicy draws the batch and runs the step, and may keep state of its own
// (poses, per-frame statistics) that checkpoints carry as named arrays.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/config_fwd.hpp"
#include "pipeline/train/checkpoint.hpp"
#include "pipeline/train/field_optimizer.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/model/scene.hpp"
#include "pipeline/config/train_config.hpp"

namespace sgnlf::pipeline {

using NamedArrays = std::vector<std::pair<std::string, std::vector<float>>>;

class StepPolicy {
 public:
  virtual ~StepPolicy() = default;
  // Before the first step of every epoch (one pass over scene.train); `step` is its first step.
  virtual void on_epoch(long epoch, long step) { (void)epoch, (void)step; }
  // The field's schedules of step `step` (the pose-free methods' coarse-to-fine level mask,
  // SG-NLF's fusion weight λ(t)). The trainer sets every policy's before the step runs, and after
  // a resume those of the checkpoint's last step (an epoch that starts right at the checkpoint
  // uses the model, for the pose graph's features, before the next step): what a policy renders
  // with does not depend on the order its wrappers are composed in. A wrapper passes it on.
  virtual void set_schedules(LidarNerfModel& model, long step) { (void)model, (void)step; }
  // One training step with the network learning rate `lr` (may only enqueue), after
  // set_schedules(model, step): the model's forward_backward, then `optim`'s step.
  virtual void step(LidarNerfModel& model, FieldOptimizer& optim, uint64_t seed, long step,
                    float lr) = 0;
  // Extra fields for train_log.jsonl at logged steps, and a short progress text.
  virtual Json log_fields();  // none by default
  virtual std::string progress_text() { return ""; }
  // Named arrays saved beside the model's in checkpoints, and their restoration.
  virtual NamedArrays state() const { return {}; }
  virtual void load_state(const Checkpoint& ck, LidarNerfModel& model) { (void)ck, (void)model; }
};

// The ground-truth-pose methods (LiDAR-NeRF, LiDAR4D): batches from scene.T_world_lidar, the
// gradient, the optimiser's step; a 4D encoder takes the batch frame's time
// (LidarNerfModel::set_frame).
class GroundTruthPoseStep : public StepPolicy {
 public:
  GroundTruthPoseStep(const Scene& scene, const TrainConfig& cfg) : scene_(scene), cfg_(cfg) {}
  void step(LidarNerfModel& model, FieldOptimizer& optim, uint64_t seed, long step,
            float lr) override {
    const RayBatch b = draw_ray_batch(scene_, cfg_, seed, step);
    model.set_frame(b.frame, int(scene_.T_world_lidar.size()));
    model.forward_backward(b, seed, step);
    optim.step(lr);
  }

 private:
  const Scene& scene_;
  const TrainConfig& cfg_;
};

}  // namespace sgnlf::pipeline
