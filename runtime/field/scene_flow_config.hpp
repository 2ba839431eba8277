// The scene-flow field's configuration (scene_flow.hpp), host-only.
#pragma once
#include <string>

#include "core/config_choices.hpp"
#include "core/config_fwd.hpp"
#include "field/hash_grid_config.hpp"

namespace sgnlf::field {

struct SceneFlowConfig {
  int levels = 8;
  int features = 8;               // per level: 1, 2, 4 or 8; a multiple of time_nodes
  int time_nodes = 4;             // B: features per level split into B chunks of F / B
  float base_resolution = 32.0f;
  float max_resolution = 8192.0f;  // finest level; growth (max / base)^(1/(levels − 1))
  int log2_table_size = 18;
  int hidden_width = 64;
  int hidden_layers = 2;          // LiDAR4D's num_layers = 3: two hidden, one output
  float out_init_std = 0.001f;
  // The grid's backward and table (field::HashGridConfig's keys of the same names).
  bool deterministic = true;
  bool half_table = false;
  std::string schedule = "auto";

  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("levels", s.levels, 1, 32);
    v("features", s.features, 1, 8);
    v("time_nodes", s.time_nodes, 2, 8);
    v("base_resolution", s.base_resolution, 1.0f, 65536.0f);
    v("max_resolution", s.max_resolution, 1.0f, 1048576.0f);
    v("log2_table_size", s.log2_table_size, 4, 24);
    v("hidden_width", s.hidden_width, 1, 128);
    v("hidden_layers", s.hidden_layers, 0, 8);
    v("out_init_std", s.out_init_std, 0.0f, 1.0f);
    v("deterministic", s.deterministic, config::omit_when(true));
    v("half_table", s.half_table, config::omit_when(false));
    v("schedule", s.schedule, config::omit_when<std::string>("auto"));
  }
  // Ranges, features divisible by time_nodes, max_resolution ≥ base_resolution.
  void validate(const std::string& where = "scene_flow") const;  // throws ConfigError
  static SceneFlowConfig from_json(const Json& j, const std::string& where);
  Json to_json() const;
  // The hash grid this configuration describes (its MLP: scene_flow_mlp_spec()).
  HashGridConfig grid_config() const;
};

}  // namespace sgnlf::field
