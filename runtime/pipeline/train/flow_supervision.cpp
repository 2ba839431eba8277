// FlowSupervision and its two classes (flow_supervision.hpp).
#include "pipeline/train/flow_supervision.hpp"

#include "render/device_scene_flow_loss.hpp"
#include "render/scene_flow_loss.hpp"

namespace sgnlf::pipeline {

FlowSupervision::FlowSupervision(const Dataset& d, const Scene& scene, const TrainConfig& c,
                                 uint64_t seed)
    : c_(c.lidar4d.value().flow.value()),
      points_(flow_points(d, scene, *c.lidar4d->flow, seed ^ 0xF10Full)),
      is_train_(d.frames.size(), false) {
  for (int f : scene.train) is_train_[size_t(f)] = true;
}

const std::vector<geometry::Point3f>* FlowSupervision::train_points(long frame) const {
  if (frame < 0 || frame >= long(points_.size()) || !is_train_[size_t(frame)]) return nullptr;
  return &points_[size_t(frame)].moving;
}

void FlowSupervision::add_field_gradient(FieldPass& field) {
  if (field.step % c_.every != 0) return;
  const int k = field.batch.frame;
  const FramePoints& p = points_[size_t(k)];
  if (p.moving.size() + p.ground.size() == 0) return;
  run(field, k);
}

namespace {

// The profile's chamfer: host.
class HostFlowSupervision final : public FlowSupervision {
 public:
  HostFlowSupervision(const Dataset& d, const Scene& scene, const TrainConfig& c, uint64_t seed)
      : FlowSupervision(d, scene, c, seed) {}
  double last_value() const override { return last_; }

 private:
  void run(FieldPass& field, int k) override {
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
    const double w = c_.weight;
    const float gw = float(c_.ground_weight);
    last_ = field.flow(x, int(m + g), [&](const std::vector<float>& flow, std::vector<float>& d_flow) {
      const std::vector<float> fm(flow.begin(), flow.begin() + long(m) * 6);
      const std::vector<float> fg(flow.begin() + long(m) * 6, flow.end());
      const render::SceneFlowLoss lm = render::scene_flow_loss(p.moving, fm, nb, c_.steps);
      const render::SceneFlowLoss lg = render::ground_flow_penalty(fg, gw);
      for (size_t i = 0; i < m * 6; ++i) d_flow[i] = float(w * lm.d_flow[i]);
      for (size_t i = 0; i < g * 6; ++i) d_flow[m * 6 + i] = lg.d_flow[i];
      return w * lm.loss + lg.loss;
    });
  }
  double last_ = 0.0;
};

// The profile's chamfer: device. Frame f's points on the device: its moving then its ground
// points (n × 3), uploaded on the first step; a neighbour frame's set is the first (moving)
// part of its buffer.
class DeviceFlowSupervision final : public FlowSupervision {
 public:
  DeviceFlowSupervision(const Dataset& d, const Scene& scene, const TrainConfig& c, uint64_t seed)
      : FlowSupervision(d, scene, c, seed) {}
  double last_value() const override {
    if (pending_) {
      last_ = loss_->read(c_.weight);
      pending_ = false;
    }
    return last_;
  }

 private:
  void run(FieldPass& field, int k) override {
    if (!loss_) upload(field.runtime());
    const FramePoints& p = points_[size_t(k)];
    const size_t m = p.moving.size(), g = p.ground.size();
    render::DeviceFlowNeighbours nb;
    for (int s = 0; s < c_.steps; ++s) {
      if (const auto* next = train_points(k + s + 1))
        nb.next[s] = &frames_[size_t(k + s + 1)], nb.n_next[s] = int(next->size());
      if (const auto* prev = train_points(k - s - 1))
        nb.prev[s] = &frames_[size_t(k - s - 1)], nb.n_prev[s] = int(prev->size());
    }
    const cl::Buffer& x = frames_[size_t(k)];
    field.flow(x, int(m + g), [&](const cl::Buffer& flow, cl::Buffer& d_flow) {
      loss_->run(x, int(m), int(g), flow, nb, c_.steps, float(c_.weight), float(c_.ground_weight),
                 d_flow);
    });
    pending_ = true;
  }
  void upload(cl::Runtime& rt) {
    loss_ = std::make_unique<render::DeviceSceneFlowLoss>(rt);
    frames_.reserve(points_.size());
    for (const FramePoints& p : points_) {
      std::vector<float> x;
      x.reserve((p.moving.size() + p.ground.size()) * 3);
      for (const auto* set : {&p.moving, &p.ground})
        for (const auto& q : *set) x.insert(x.end(), {q.x(), q.y(), q.z()});
      frames_.push_back(cl::Buffer::from(rt, x));
    }
  }
  std::unique_ptr<render::DeviceSceneFlowLoss> loss_;
  std::vector<cl::Buffer> frames_;
  mutable double last_ = 0.0;
  mutable bool pending_ = false;
};

}  // namespace

std::unique_ptr<FlowSupervision> make_flow_supervision(cl::ChamferSearch where, const Dataset& d,
                                                       const Scene& scene, const TrainConfig& c,
                                                       uint64_t seed) {
  if (where == cl::ChamferSearch::Device)
    return std::make_unique<DeviceFlowSupervision>(d, scene, c, seed);
  return std::make_unique<HostFlowSupervision>(d, scene, c, seed);
}

}  // namespace sgnlf::pipeline
