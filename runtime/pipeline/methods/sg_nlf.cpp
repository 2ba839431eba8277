// SG-NLF (method.md §4): GeoNLF's pose-free step on the hybrid field, with the confidence-aware
// pose graph in the geometric stage and the adversarial cross-frame consistency.
#include "pipeline/methods/methods.hpp"

namespace sgnlf::pipeline::methods {

Method sg_nlf() {
  Method m;
  m.name = "sg-nlf";
  m.description =
      "SG-NLF (method.md §4): hybrid field, confidence-aware pose graph, adversarial "
      "cross-frame consistency";
  m.preset_family = "sg-nlf";
  m.sections.pose_free = true;
  m.sections.spectral = true;
  m.sections.pose_graph = true;
  m.sections.consistency = true;
  m.implemented = true;
  m.compose = [](StepParts& p) -> StepPolicy& {
    return p.spectral(p.consistency(p.pose_free()));
  };
  return m;
}

}  // namespace sgnlf::pipeline::methods
