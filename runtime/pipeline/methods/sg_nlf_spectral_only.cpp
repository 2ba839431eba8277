// Ablation (method.md §5): SG-NLF's field without the hash grid, the spectral embedding alone.
#include "core/config.hpp"
#include "pipeline/methods/methods.hpp"

namespace sgnlf::pipeline::methods {

Method sg_nlf_spectral_only() {
  Method m = sg_nlf();
  m.name = "sg-nlf-spectral-only";
  m.description =
      "SG-NLF with the spectral embedding alone (method.md §5 ablation): Psi(x) feeds the density "
      "MLP and the pose graph's matching without the hash grid, at full weight from the first "
      "step (there is nothing to fuse it with)";
  m.overrides = Json{{"method", m.name},
                     {"spectral", {{"geometric", false}, {"fusion", {{"start", 0}, {"end", 0}}}}}};
  return m;
}

}  // namespace sgnlf::pipeline::methods
