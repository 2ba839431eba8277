// LiDAR4D's scene-flow supervision as a step around another (method.md §2; LiDAR4D
// model/runner.py): before every `every`-th step, the flow field at the batch frame's
// ground-removed points (flow_points.hpp), moved forward and backward, is compared with the
// neighbouring training frames' points (render/scene_flow_loss.hpp, weight), and its flow on the
// ground points is pulled to zero (ground_weight). Its gradient is pending on the model and
// joins the inner step's update. Neighbours are training frames only (a test frame's scan is
// never seen in training); a missing one contributes nothing, as in LiDAR4D.
// Under the device profile's chamfer: device (LidarNerfModel::chamfer_on_device) every frame's
// points are uploaded once (first step), and the flow, its loss (render::DeviceSceneFlowLoss)
// and gradient stay on the device: the step reads nothing back, and the flow loss and the
// Chamfer term's value are read when asked (log_fields(), last_flow_loss()).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "datasets/dataset.hpp"
#include "pipeline/train/flow_points.hpp"
#include "pipeline/train/step_policy.hpp"

namespace sgnlf::pipeline {

class FlowSupervisionStep : public StepPolicy {
 public:
  FlowSupervisionStep(StepPolicy& inner, const Dataset& d, const Scene& scene,
                      const TrainConfig& c, uint64_t seed);
  ~FlowSupervisionStep() override;

  void on_epoch(long epoch, long step) override { inner_.on_epoch(epoch, step); }
  void step(LidarNerfModel& model, uint64_t seed, long step, float lr) override;
  Json log_fields() override;
  std::string progress_text() override { return inner_.progress_text(); }
  NamedArrays state() const override { return inner_.state(); }
  void load_state(const Checkpoint& ck, LidarNerfModel& model) override {
    inner_.load_state(ck, model);
  }

  // The flow loss of the last flow step (0 before the first); device: one blocking read.
  double last_flow_loss() const;
  const std::vector<FramePoints>& points() const { return points_; }

 private:
  StepPolicy& inner_;
  const Scene& scene_;
  const FlowSupervisionConfig& c_;
  std::vector<FramePoints> points_;
  std::vector<bool> is_train_;
  mutable double last_loss_ = 0.0;
  double last_chamfer_ = 0.0;
  const std::vector<geometry::Point3f>* train_points(long frame) const;
  // chamfer: device: the frames' points on the device, the loss's launcher, its pending value.
  struct Device;
  std::unique_ptr<Device> device_;
  mutable bool loss_on_device_ = false;
  LidarNerfModel* model_ = nullptr;  // the last step's (its Chamfer value, read when logged)
  void device_step(LidarNerfModel& model, int k);
};

}  // namespace sgnlf::pipeline
