// FlowSupervisionStep (flow_supervision.hpp).
#include "pipeline/train/flow_supervision.hpp"

#include "core/config.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "render/device_scene_flow_loss.hpp"
#include "render/scene_flow_loss.hpp"

namespace sgnlf::pipeline {

// Frame f's points on the device: its moving then its ground points (n × 3), uploaded once; a
// neighbour frame's set is the first (moving) part of its buffer.
struct FlowSupervisionStep::Device {
  std::vector<cl::Buffer> frames;
  render::DeviceSceneFlowLoss loss;
  Device(cl::Runtime& rt, const std::vector<FramePoints>& points) : loss(rt) {
    frames.reserve(points.size());
    for (const FramePoints& p : points) {
      std::vector<float> x;
      x.reserve((p.moving.size() + p.ground.size()) * 3);
      for (const auto* set : {&p.moving, &p.ground})
        for (const auto& q : *set) x.insert(x.end(), {q.x(), q.y(), q.z()});
      frames.push_back(cl::Buffer::from(rt, x));
    }
  }
};

FlowSupervisionStep::~FlowSupervisionStep() = default;

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

void FlowSupervisionStep::device_step(LidarNerfModel& model, int k) {
  if (!device_) device_ = std::make_unique<Device>(model.runtime(), points_);
  const FramePoints& p = points_[size_t(k)];
  const size_t m = p.moving.size(), g = p.ground.size();
  model.set_frame(k, int(scene_.T_world_lidar.size()));
  if (m + g == 0) return;
  render::DeviceFlowNeighbours nb;
  for (int s = 0; s < c_.steps; ++s) {
    if (const auto* next = train_points(k + s + 1))
      nb.next[s] = &device_->frames[size_t(k + s + 1)], nb.n_next[s] = int(next->size());
    if (const auto* prev = train_points(k - s - 1))
      nb.prev[s] = &device_->frames[size_t(k - s - 1)], nb.n_prev[s] = int(prev->size());
  }
  const cl::Buffer& x = device_->frames[size_t(k)];
  model.flow_supervision_device(x, int(m + g), [&](const cl::Buffer& flow, cl::Buffer& d_flow) {
    device_->loss.run(x, int(m), int(g), flow, nb, c_.steps, float(c_.weight),
                      float(c_.ground_weight), d_flow);
  });
  loss_on_device_ = true;
}

double FlowSupervisionStep::last_flow_loss() const {
  if (loss_on_device_) {
    last_loss_ = device_->loss.read(c_.weight);
    loss_on_device_ = false;
  }
  return last_loss_;
}

void FlowSupervisionStep::step(LidarNerfModel& model, uint64_t seed, long step, float lr) {
  model_ = &model;
  if (step % c_.every == 0 && model.chamfer_on_device()) {
    device_step(model, batch_frame(scene_, seed, step));
  } else if (step % c_.every == 0) {
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
  if (!model.chamfer_on_device()) last_chamfer_ = model.last_chamfer();
}

Json FlowSupervisionStep::log_fields() {
  Json j = inner_.log_fields();
  j["flow_loss"] = last_flow_loss();
  j["chamfer_loss"] =
      model_ && model_->chamfer_on_device() ? model_->last_chamfer() : last_chamfer_;
  return j;
}

}  // namespace sgnlf::pipeline
