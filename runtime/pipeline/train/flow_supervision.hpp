// LiDAR4D's scene-flow supervision as a step around another (method.md §2; LiDAR4D
// model/runner.py): before every `every`-th step, the flow field at the batch frame's
// ground-removed points (flow_points.hpp), moved forward and backward, is compared with the
// neighbouring training frames' points (render/scene_flow_loss.hpp, weight), and its flow on the
// ground points is pulled to zero (ground_weight). Its gradient is pending on the model and
// joins the inner step's update. Neighbours are training frames only (a test frame's scan is
// never seen in training); a missing one contributes nothing, as in LiDAR4D.
#pragma once
#include <cstdint>
#include <vector>

#include "datasets/dataset.hpp"
#include "pipeline/train/flow_points.hpp"
#include "pipeline/train/step_policy.hpp"

namespace sgnlf::pipeline {

class FlowSupervisionStep : public StepPolicy {
 public:
  FlowSupervisionStep(StepPolicy& inner, const Dataset& d, const Scene& scene,
                      const TrainConfig& c, uint64_t seed);

  void on_epoch(long epoch, long step) override { inner_.on_epoch(epoch, step); }
  void step(LidarNerfModel& model, uint64_t seed, long step, float lr) override;
  Json log_fields() override;
  std::string progress_text() override { return inner_.progress_text(); }
  NamedArrays state() const override { return inner_.state(); }
  void load_state(const Checkpoint& ck, LidarNerfModel& model) override {
    inner_.load_state(ck, model);
  }

  double last_flow_loss() const { return last_loss_; }
  const std::vector<FramePoints>& points() const { return points_; }

 private:
  StepPolicy& inner_;
  const Scene& scene_;
  const FlowSupervisionConfig& c_;
  std::vector<FramePoints> points_;
  std::vector<bool> is_train_;
  double last_loss_ = 0.0, last_chamfer_ = 0.0;
  const std::vector<geometry::Point3f>* train_points(long frame) const;
};

}  // namespace sgnlf::pipeline
