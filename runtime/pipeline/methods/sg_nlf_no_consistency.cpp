// Ablation (method.md §5): SG-NLF without the adversarial cross-frame consistency. Its config
// has no "consistency" section at all, so its config and hash are those of a method that never
// had the term.
#include "core/config.hpp"
#include "pipeline/methods/methods.hpp"

namespace sgnlf::pipeline::methods {

Method sg_nlf_no_consistency() {
  Method m = sg_nlf();
  m.name = "sg-nlf-no-consistency";
  m.description =
      "SG-NLF without the adversarial cross-frame consistency (method.md §5 ablation): hybrid "
      "field and confidence-aware pose graph";
  m.overrides = Json{{"method", m.name}};
  m.sections.consistency = false;
  return m;
}

}  // namespace sgnlf::pipeline::methods
