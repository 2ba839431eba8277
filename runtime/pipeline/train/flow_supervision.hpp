// LiDAR4D's scene-flow supervision as a loss term of the model (method.md §2; LiDAR4D
// model/runner.py): at every `every`-th step, in the term's own pass ahead of the batch's
// (loss_term.hpp's FieldPass::flow), the flow field at the batch frame's ground-removed points
// (flow_points.hpp), moved forward and backward, is compared with the neighbouring training
// frames' points (render/scene_flow_loss.hpp, weight), and its flow on the ground points is
// pulled to zero (ground_weight). The flow is evaluated at the batch frame's time, which the
// step sets before it calls the model. Neighbours are training frames only (a test frame's scan
// is never seen in training); a missing one contributes nothing, as in LiDAR4D. Reports "flow"
// (the last flow step's value).
// The device profile's chamfer chooses the term's class once (make_flow_supervision): host =
// the flow read back, the neighbours by geometry::KdTree, the gradient written back; device =
// every frame's points uploaded once (first step), the flow, its loss
// (render::DeviceSceneFlowLoss) and gradient on the device, nothing read back but the value
// when reported.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "cl/device_profile.hpp"
#include "datasets/dataset.hpp"
#include "pipeline/config/train_config.hpp"
#include "pipeline/model/loss_term.hpp"
#include "pipeline/model/scene.hpp"
#include "pipeline/train/flow_points.hpp"

namespace sgnlf::pipeline {

class FlowSupervision : public LossTerm {
 public:
  const char* name() const override { return "flow"; }
  void add_field_gradient(FieldPass& field) override;
  void report(LossReport& r, const std::vector<float>&) const override {
    r.add("flow", last_value());
  }
  // The value of the last flow step (0 before the first); device: one blocking read.
  virtual double last_value() const = 0;
  const std::vector<FramePoints>& points() const { return points_; }

 protected:
  FlowSupervision(const Dataset& d, const Scene& scene, const TrainConfig& c, uint64_t seed);
  // One flow step on frame k's points (moving then ground: m + g > 0).
  virtual void run(FieldPass& field, int k) = 0;
  // Frame `frame`'s moving points when it is a training frame, else null.
  const std::vector<geometry::Point3f>* train_points(long frame) const;

  const FlowSupervisionConfig& c_;
  std::vector<FramePoints> points_;

 private:
  std::vector<bool> is_train_;
};

std::unique_ptr<FlowSupervision> make_flow_supervision(cl::ChamferSearch where, const Dataset& d,
                                                       const Scene& scene, const TrainConfig& c,
                                                       uint64_t seed);

}  // namespace sgnlf::pipeline
