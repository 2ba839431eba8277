// PoseGraphConfig (pose_graph_config.hpp).
#include "pipeline/config/pose_graph_config.hpp"

#include "core/config.hpp"
#include "core/config_fields.hpp"
#include "core/error.hpp"

namespace sgnlf::pipeline {

void PoseGraphConfig::validate(const std::string& where) const {
  config::check_fields(*this, where + ".pose_graph");
  graph.validate();
}

PoseGraphConfig PoseGraphConfig::from_json(ConfigReader& r) {
  PoseGraphConfig c;
  auto s = r.child("pose_graph");
  config::refuse_enabled_key(s, "pose_graph");
  config::read_fields_here(s, c);
  c.graph = posegraph::ConfidenceGraphConfig::from_json(s);
  s.finish();
  return c;
}

void PoseGraphConfig::to_json(Json& j) const {
  Json g = graph.to_json();
  g.update(config::write_fields(*this));
  j["pose_graph"] = g;
}

}  // namespace sgnlf::pipeline
