// PoseGraphConfig (pose_graph_config.hpp).
#include "pipeline/pose_graph_config.hpp"

#include "core/error.hpp"

namespace sgnlf::pipeline {

void PoseGraphConfig::validate(const std::string& where) const {
  check_range(where + ".pose_graph", "start_epoch", start_epoch, 1, 100000000);
  check_range(where + ".pose_graph", "steps_on_build", steps_on_build, 0, 1000000);
  check_range(where + ".pose_graph", "lr_on_build", lr_on_build, 1e-6, 1.0);
  graph.validate();
}

PoseGraphConfig PoseGraphConfig::from_json(ConfigReader& r) {
  PoseGraphConfig c;
  if (!r.has("pose_graph")) return c;
  auto s = r.child("pose_graph");
  s.get("enabled", c.enabled).get("start_epoch", c.start_epoch);
  s.get("steps_on_build", c.steps_on_build).get("lr_on_build", c.lr_on_build);
  c.graph = posegraph::ConfidenceGraphConfig::from_json(s);
  s.finish();
  return c;
}

void PoseGraphConfig::to_json(Json& j) const {
  Json g = graph.to_json();
  g["enabled"] = enabled;
  g["start_epoch"] = start_epoch;
  g["steps_on_build"] = steps_on_build;
  g["lr_on_build"] = lr_on_build;
  j["pose_graph"] = g;
}

}  // namespace sgnlf::pipeline
