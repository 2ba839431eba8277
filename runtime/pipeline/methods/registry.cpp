// The method registry (see registry.hpp).
#include "pipeline/methods/registry.hpp"

#include "pipeline/methods/methods.hpp"

namespace sgnlf::pipeline {

const std::vector<Method>& method_registry() {
  static const std::vector<Method> registry = {
      methods::lidar_nerf(),       methods::lidar4d(),
      methods::geonlf(),           methods::geonlf_frozen(),
      methods::sg_nlf(),           methods::sg_nlf_no_consistency(),
      // The other one-switch ablations of method.md §5 (the ablation-nuscenes table).
      methods::sg_nlf_no_hybrid(), methods::sg_nlf_no_graph(),
      methods::sg_nlf_baseline(),  methods::sg_nlf_spectral_only(),
      // The control beside SG-NLF: its field on the ground-truth poses.
      methods::sg_nlf_gt_poses(),
  };
  return registry;
}

const Method& find_method(const std::string& name) {
  std::string known;
  for (const auto& m : method_registry()) {
    if (m.name == name) return m;
    known += (known.empty() ? "" : ", ") + m.name;
  }
  throw ConfigError("unknown method '" + name + "' (known: " + known + ")");
}

}  // namespace sgnlf::pipeline
