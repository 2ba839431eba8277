// Ablation (method.md §5): SG-NLF without the hybrid representation.
#include "core/config.hpp"
#include "pipeline/methods/methods.hpp"

namespace sgnlf::pipeline::methods {

Method sg_nlf_no_hybrid() {
  Method m = sg_nlf();
  m.name = "sg-nlf-no-hybrid";
  m.description =
      "SG-NLF without the hybrid representation (method.md §5 ablation): the hash grid alone "
      "feeds the density MLP and the pose graph's matching";
  m.overrides = Json{{"method", m.name}};
  m.sections.spectral = false;  // no "spectral" section: the plain hash grid
  return m;
}

}  // namespace sgnlf::pipeline::methods
