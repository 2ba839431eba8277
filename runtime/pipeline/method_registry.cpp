// The method registry (see method_registry.hpp).
#include "pipeline/method_registry.hpp"

namespace sgnlf::pipeline {

const std::vector<MethodSpec>& method_registry() {
  static const std::vector<MethodSpec> registry = {
      {"lidar-nerf", "lidar-nerf", Json::object(), false, true,
       "LiDAR-NeRF with ground-truth poses (method.md §1)"},
      {"lidar4d", "lidar4d", Json::object(), false, false,
       "LiDAR4D with ground-truth poses (method.md §2)"},
      {"geonlf", "geonlf", Json::object(), true, true,
       "GeoNLF: poses optimised jointly with the field, geometric optimiser (method.md §3)"},
      {"geonlf-frozen", "geonlf",
       Json{{"method", "geonlf-frozen"},
            {"pose_optim", {{"optimize", false}}},
            {"geometric", {{"enabled", false}}}},
       true, true,
       "control (not in the paper): GeoNLF's field trained on the frozen initial poses"},
      {"sg-nlf", "sg-nlf", Json::object(), true, true,
       "SG-NLF (method.md §4): hybrid field, confidence-aware pose graph, adversarial "
       "cross-frame consistency",
       true, true, true},
      {"sg-nlf-no-consistency", "sg-nlf", Json{{"method", "sg-nlf-no-consistency"}}, true, true,
       "SG-NLF without the adversarial cross-frame consistency (method.md §5 ablation): hybrid "
       "field and confidence-aware pose graph",
       true, true},
      // The other one-switch ablations of method.md §5 (the ablation-nuscenes table).
      {"sg-nlf-no-hybrid", "sg-nlf",
       Json{{"method", "sg-nlf-no-hybrid"}, {"spectral", {{"enabled", false}}}}, true, true,
       "SG-NLF without the hybrid representation (method.md §5 ablation): the hash grid alone "
       "feeds the density MLP and the pose graph's matching",
       true, true, true},
      {"sg-nlf-no-graph", "sg-nlf",
       Json{{"method", "sg-nlf-no-graph"}, {"pose_graph", {{"enabled", false}}}}, true, true,
       "SG-NLF without the global pose graph (method.md §5 ablation): sequential edges only",
       true, true, true},
      {"sg-nlf-baseline", "sg-nlf",
       Json{{"method", "sg-nlf-baseline"},
            {"spectral", {{"enabled", false}}},
            {"pose_graph", {{"enabled", false}}}},
       true, true,
       "SG-NLF's baseline (method.md §5 ablation): pairwise sequential edges only, no spectral "
       "embedding, no adversarial term",
       true, true},
  };
  return registry;
}

const MethodSpec& method_spec(const std::string& name) {
  std::string known;
  for (const auto& m : method_registry()) {
    if (m.name == name) return m;
    known += (known.empty() ? "" : ", ") + m.name;
  }
  throw ConfigError("unknown method '" + name + "' (known: " + known + ")");
}

}  // namespace sgnlf::pipeline
