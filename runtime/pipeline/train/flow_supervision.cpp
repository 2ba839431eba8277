// FlowSupervisionStep (flow_supervision.hpp).
#include "pipeline/train/flow_supervision.hpp"

#include "core/config.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "render/scene_flow_loss.hpp"

namespace sgnlf::pipeline {

FlowSupervisionStep::FlowSupervisionStep(StepPolicy& inner, const Dataset& d, const Scene& scene,
                                         const TrainConfig& c, uint64_t seed)
    : inner_(inner), scene_(scene), c_(c.lidar4d.value().flow.value()),
      points_(flow_points(d, scene, *c.lidar4d->flow, seed ^ 0xF10Full)),
      is_train_(d.frames.size(), false) {
  for (int f : scene.train) is_train_[size_t(f)] = true;
}

const std::vector<geometry::Point3f>* FlowSupervisionStep::train_points(long frame) const {
  if (frame < 0 || frame >= long(points_.size()) || !is_train_[size_t(frame)]) return nullptr;
  return &points_[size_t(frame)].moving;
}

void FlowSupervisionStep::step(LidarNerfModel& model, uint64_t seed, long step, float lr) {
  if (step % c_.every == 0) {
    const int k = batch_frame(scene_, seed, step);  // the frame the inner step trains on
    const FramePoints& p = points_[size_t(k)];
    render::FlowNeighbours nb;
    for (int s = 0; s < c_.steps; ++s) {
      nb.next[s] = train_points(k + s + 1);
      nb.prev[s] = train_points(k - s - 1);
    }
    const size_t m = p.moving.size(), g = p.ground.size();
    std::vector<float> x;
    x.reserve((m + g) * 3);
    for (const auto* set : {&p.moving, &p.ground})
      for (const auto& q : *set) x.insert(x.end(), {q.x(), q.y(), q.z()});
    model.set_frame(k, int(scene_.T_world_lidar.size()));
    const double w = c_.weight;
    const float gw = float(c_.ground_weight);
    if (m + g > 0)
      last_loss_ = model.flow_supervision(
          x, int(m + g), [&](const std::vector<float>& flow, std::vector<float>& d_flow) {
            const std::vector<float> fm(flow.begin(), flow.begin() + long(m) * 6);
            const std::vector<float> fg(flow.begin() + long(m) * 6, flow.end());
            const render::SceneFlowLoss lm = render::scene_flow_loss(p.moving, fm, nb, c_.steps);
            const render::SceneFlowLoss lg = render::ground_flow_penalty(fg, gw);
            for (size_t i = 0; i < m * 6; ++i) d_flow[i] = float(w * lm.d_flow[i]);
            for (size_t i = 0; i < g * 6; ++i) d_flow[m * 6 + i] = lg.d_flow[i];
            return w * lm.loss + lg.loss;
          });
  }
  inner_.step(model, seed, step, lr);
  last_chamfer_ = model.last_chamfer();
}

Json FlowSupervisionStep::log_fields() {
  Json j = inner_.log_fields();
  j["flow_loss"] = last_loss_;
  j["chamfer_loss"] = last_chamfer_;
  return j;
}

}  // namespace sgnlf::pipeline
