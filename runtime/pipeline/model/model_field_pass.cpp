// FieldPass (loss_term.hpp): a loss term's own pass through LidarNerfModel's field within a
// training step, before the batch's: rays rendered and differentiated, or the flow field
// evaluated, into the step's second gradient (LidarNerfModel::own_gradient), which
// forward_backward adds to the batch's.
#include <algorithm>
#include <string>

#include "core/error.hpp"
#include "field/lidar4d_encoder.hpp"
#include "pipeline/model/model.hpp"

namespace sgnlf::pipeline {

cl::Runtime& FieldPass::runtime() const { return model_.rt_; }

void FieldPass::claim(const char* who) {
  if (wrote_)
    throw Error(std::string(who) + ": another loss term wrote this step's second gradient already");
  wrote_ = true;
}

RenderedRays FieldPass::render(const std::vector<float>& origins,
                               const std::vector<float>& directions, int n) {
  LidarNerfModel& m = model_;
  require(n > 0 && n <= m.max_rays_, "FieldPass::render: " + std::to_string(n) +
                                         " rays, capacity " + std::to_string(m.max_rays_));
  require(origins.size() == size_t(n) * 3 && directions.size() == size_t(n) * 3,
          "FieldPass::render: origins/directions must hold n × 3 floats");
  m.o_.write_vec(origins);
  m.d_.write_vec(directions);
  RenderedRays r;
  r.context = m.forward(m.sample(*m.protocol_, n, m.cfg_.render.jitter, seed, uint32_t(step)));
  r.out = m.out_.read_vec<float>(size_t(n) * 3);
  r.n = n;
  return r;
}

RayGrads FieldPass::backward(const RenderedRays& rays, const std::vector<float>& grad_out,
                             bool ray_grads) {
  LidarNerfModel& m = model_;
  require(grad_out.size() == size_t(rays.n) * 3,
          "FieldPass::backward: " + std::to_string(grad_out.size()) + " floats for " +
              std::to_string(rays.n) + " rays × 3");
  if (!rays.context.valid() || rays.context.pass != m.pass_)
    throw Error("FieldPass::backward: the rays' activations were overwritten by a later pass");
  claim("FieldPass::backward");
  cl::Buffer& grad = m.own_gradient();
  m.grad_out_.write_vec(grad_out);
  m.backward(rays.context, grad, ray_grads, nullptr);
  m.own_full_ = true;
  m.begin_pass();  // differentiated once: a second backward of these rays throws
  return ray_grads ? m.read_ray_grads() : RayGrads{};
}

double FieldPass::flow(const std::vector<float>& x, int n, const FlowLoss& loss) {
  LidarNerfModel& m = model_;
  require(n > 0 && x.size() == size_t(n) * 3,
          "FieldPass::flow: " + std::to_string(x.size()) + " floats for " + std::to_string(n) +
              " points");
  claim("FieldPass::flow");
  field::SceneFlow& flow = m.begin_flow(n, "FieldPass::flow");
  const size_t off = m.off_grid_ + m.four_d_->offsets().flow;
  m.fx_.write_vec(x);
  m.ft_.write_vec(std::vector<float>(size_t(n), m.four_d_->time()));
  flow.forward(m.params_, off, m.fx_, m.ft_, n, m.fflow_);
  const std::vector<float> f = m.fflow_.read_vec<float>(size_t(n) * 6);
  std::vector<float> d_flow(size_t(n) * 6, 0.0f);
  const double value = loss(f, d_flow);
  require(d_flow.size() == size_t(n) * 6,
          "FieldPass::flow: the loss wrote " + std::to_string(d_flow.size()) + " gradients");
  m.fdflow_.write_vec(d_flow);
  flow.backward(m.params_, off, m.fx_, m.ft_, n, m.fflow_, m.fdflow_, m.grad_own_, off);
  return value;
}

void FieldPass::flow(const cl::Buffer& x, int n, const DeviceFlowLoss& loss) {
  LidarNerfModel& m = model_;
  require(n > 0 && x.bytes() >= size_t(n) * 3 * sizeof(float),
          "FieldPass::flow: " + std::to_string(x.bytes() / sizeof(float)) + " floats for " +
              std::to_string(n) + " points");
  claim("FieldPass::flow");
  field::SceneFlow& flow = m.begin_flow(n, "FieldPass::flow");
  const size_t off = m.off_grid_ + m.four_d_->offsets().flow;
  float* t = m.up_ft_.stage<float>(size_t(n));
  std::fill(t, t + n, m.four_d_->time());
  m.up_ft_.write(m.ft_);
  flow.forward(m.params_, off, x, m.ft_, n, m.fflow_);
  loss(m.fflow_, m.fdflow_);
  flow.backward(m.params_, off, x, m.ft_, n, m.fflow_, m.fdflow_, m.grad_own_, off);
}

}  // namespace sgnlf::pipeline
