// LidarNerfModel's LiDAR4D parts (model.hpp): the frame time of the 4D encoder and the flow
// supervision's pass through the flow field (method.md §2; the Chamfer term is a loss term,
// loss_terms.hpp).
#include <algorithm>
#include <string>

#include "core/error.hpp"
#include "field/lidar4d_encoder.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/model/model_detail.hpp"

namespace sgnlf::pipeline {
using namespace model_detail;

void LidarNerfModel::set_frame(int frame, int frames) {
  if (four_d_) four_d_->set_frame(frame, 0, frames);
}

field::SceneFlow& LidarNerfModel::begin_flow(int n, const char* who) {
  if (!four_d_) throw Error(std::string(who) + ": the model has no 4D encoder");
  if (n > flow_cap_) {
    fx_ = floats(rt_, size_t(n) * 3), ft_ = floats(rt_, size_t(n));
    fflow_ = floats(rt_, size_t(n) * 6), fdflow_ = floats(rt_, size_t(n) * 6);
    flow_cap_ = n;
  }
  if (!grad_ext_) {
    grad_ext_ = floats(rt_, layout_.total());
    add_k_ = rt_.kernel("field/accumulate.cl", "field_accumulate");
    ext_full_ = true;
  }
  if (ext_pending_) throw Error(std::string(who) + ": an external gradient is already pending");
  if (ext_full_) {  // backward_external wrote every slice: only the flow slice may be non-zero
    grad_ext_.fill_zero();
    ext_full_ = false;
  }
  return four_d_->flow();
}

double LidarNerfModel::flow_supervision(const std::vector<float>& x, int n, const FlowLoss& loss) {
  if (!four_d_) throw Error("LidarNerfModel::flow_supervision: the model has no 4D encoder");
  require(n > 0 && x.size() == size_t(n) * 3,
          "LidarNerfModel::flow_supervision: " + std::to_string(x.size()) + " floats for " +
              std::to_string(n) + " points");
  field::SceneFlow& flow = begin_flow(n, "LidarNerfModel::flow_supervision");
  const size_t off = off_grid_ + four_d_->offsets().flow;
  fx_.write_vec(x);
  ft_.write_vec(std::vector<float>(size_t(n), four_d_->time()));
  flow.forward(params_, off, fx_, ft_, n, fflow_);
  const std::vector<float> f = fflow_.read_vec<float>(size_t(n) * 6);
  std::vector<float> d_flow(size_t(n) * 6, 0.0f);
  const double value = loss(f, d_flow);
  require(d_flow.size() == size_t(n) * 6, "LidarNerfModel::flow_supervision: the loss wrote " +
                                              std::to_string(d_flow.size()) + " gradients");
  fdflow_.write_vec(d_flow);
  flow.backward(params_, off, fx_, ft_, n, fflow_, fdflow_, grad_ext_, off);
  ext_pending_ = true;
  return value;
}

void LidarNerfModel::flow_supervision_device(const cl::Buffer& x, int n,
                                             const DeviceFlowLoss& loss) {
  const char* who = "LidarNerfModel::flow_supervision_device";
  if (!four_d_) throw Error(std::string(who) + ": the model has no 4D encoder");
  require(n > 0 && x.bytes() >= size_t(n) * 3 * sizeof(float),
          std::string(who) + ": " + std::to_string(x.bytes() / sizeof(float)) +
              " floats for " + std::to_string(n) + " points");
  field::SceneFlow& flow = begin_flow(n, who);
  const size_t off = off_grid_ + four_d_->offsets().flow;
  float* t = up_ft_.stage<float>(size_t(n));
  std::fill(t, t + n, four_d_->time());
  up_ft_.write(ft_);
  flow.forward(params_, off, x, ft_, n, fflow_);
  loss(fflow_, fdflow_);
  flow.backward(params_, off, x, ft_, n, fflow_, fdflow_, grad_ext_, off);
  ext_pending_ = true;
}

}  // namespace sgnlf::pipeline
