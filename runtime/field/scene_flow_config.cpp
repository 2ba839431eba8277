// SceneFlowConfig (scene_flow_config.hpp): checks, JSON reading and its hash grid.
#include "core/config_fields.hpp"
#include "field/scene_flow_config.hpp"

#include <cmath>
#include <string>

#include "core/config.hpp"
#include "core/error.hpp"
#include "field/feature_count.hpp"

namespace sgnlf::field {

void SceneFlowConfig::validate(const std::string& where) const {
  config::check_fields(*this, where);
  check_feature_count(where, features);
  HashGridConfig grid;  // the schedule's name, checked as the grid checks it
  grid.schedule = schedule;
  grid.validate(where);
  if (features % time_nodes != 0)
    throw ConfigError(where + ": 'time_nodes' = " + std::to_string(time_nodes) +
                      " must divide 'features' = " + std::to_string(features));
  if (max_resolution < base_resolution)
    throw ConfigError(where + ": 'max_resolution' = " + std::to_string(max_resolution) +
                      " is below 'base_resolution' = " + std::to_string(base_resolution));
}

SceneFlowConfig SceneFlowConfig::from_json(const Json& j, const std::string& where) {
  SceneFlowConfig c;
  ConfigReader r(j, where);
  config::read_fields_here(r, c);
  r.finish();
  c.validate(where);
  return c;
}

HashGridConfig SceneFlowConfig::grid_config() const {
  validate();
  HashGridConfig g;
  g.levels = levels;
  g.features = features;
  g.log2_table_size = log2_table_size;
  g.base_resolution = base_resolution;
  g.deterministic = deterministic;
  g.half_table = half_table;
  g.schedule = schedule;
  g.per_level_scale =
      levels > 1 ? float(std::exp2(std::log2(double(max_resolution) / base_resolution) /
                                   double(levels - 1)))
                 : 1.0f;
  return g;
}

Json SceneFlowConfig::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::field
