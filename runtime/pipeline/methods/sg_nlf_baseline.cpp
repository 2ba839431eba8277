// Ablation (method.md §5): SG-NLF's baseline, all three of its additions off.
#include "core/config.hpp"
#include "pipeline/methods/methods.hpp"

namespace sgnlf::pipeline::methods {

Method sg_nlf_baseline() {
  Method m = sg_nlf_no_consistency();
  m.name = "sg-nlf-baseline";
  m.description =
      "SG-NLF's baseline (method.md §5 ablation): pairwise sequential edges only, no spectral "
      "embedding, no adversarial term";
  m.overrides = Json{{"method", m.name}};
  m.sections.spectral = false;
  m.sections.pose_graph = false;
  return m;
}

}  // namespace sgnlf::pipeline::methods
