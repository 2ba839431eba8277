// Ablation (method.md §5): SG-NLF without the global pose graph.
#include "core/config.hpp"
#include "pipeline/methods/methods.hpp"

namespace sgnlf::pipeline::methods {

Method sg_nlf_no_graph() {
  Method m = sg_nlf();
  m.name = "sg-nlf-no-graph";
  m.description =
      "SG-NLF without the global pose graph (method.md §5 ablation): sequential edges only";
  m.overrides = Json{{"method", m.name}};
  m.sections.pose_graph = false;  // no "pose_graph" section: the sequential graph throughout
  return m;
}

}  // namespace sgnlf::pipeline::methods
