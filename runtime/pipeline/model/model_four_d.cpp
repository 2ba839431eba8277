// LidarNerfModel's LiDAR4D parts (model.hpp): the frame time of the 4D encoder and the buffers of
// the flow supervision's pass through the flow field (method.md §2; the pass itself is
// FieldPass::flow, model_field_pass.cpp; the Chamfer term is a loss term, loss_terms.hpp).
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
  if (!grad_own_) own_full_ = true;  // a new buffer: cleared below
  own_gradient();
  if (own_full_) {  // a rendered rays' backward wrote every slice: only the flow slice may be non-zero
    grad_own_.fill_zero();
    own_full_ = false;
  }
  return four_d_->flow();
}

cl::Buffer& LidarNerfModel::own_gradient() {
  if (!grad_own_) {
    grad_own_ = floats(rt_, layout_.total());
    grad_own_.fill_zero();  // alignment gaps between the slices stay zero
    add_k_ = rt_.kernel("field/accumulate.cl", "field_accumulate");
  }
  return grad_own_;
}

}  // namespace sgnlf::pipeline
