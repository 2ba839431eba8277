// Control row (not in the paper): SG-NLF's field (hybrid encoder, cross-frame consistency) trained
// on the ground-truth poses, held fixed. Beside SG-NLF it measures the paper's claim that the
// pose-free run is as good as one on the true poses (on the real scene too).
#include "core/config.hpp"
#include "pipeline/methods/methods.hpp"

namespace sgnlf::pipeline::methods {

Method sg_nlf_gt_poses() {
  Method m = sg_nlf();
  m.name = "sg-nlf-gt-poses";
  m.description =
      "control (not in the paper): SG-NLF's field trained on the ground-truth poses, held fixed";
  m.overrides = Json{{"method", m.name},
                     {"poses", {{"init", "gt"}}},
                     {"pose_optim", {{"optimize", false}}},
                     {"geometric", nullptr}};  // no geometric stage
  m.sections.pose_graph = false;
  return m;
}

}  // namespace sgnlf::pipeline::methods
