// GeoNLF (method.md §3): the poses are parameters optimised jointly with the field, with the
// geometric optimiser before each epoch.
#include "pipeline/methods/methods.hpp"

namespace sgnlf::pipeline::methods {

Method geonlf() {
  Method m;
  m.name = "geonlf";
  m.description =
      "GeoNLF: poses optimised jointly with the field, geometric optimiser (method.md §3)";
  m.preset_family = "geonlf";
  m.sections.pose_free = true;
  m.implemented = true;
  m.compose = [](StepParts& p) -> StepPolicy& { return p.pose_free(); };
  return m;
}

}  // namespace sgnlf::pipeline::methods
