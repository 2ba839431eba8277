// LiDAR4D's 4D encoder configuration (lidar4d_encoder.hpp), host-only: the training config's
// "lidar4d" section carries one, read and checked without the OpenCL launchers.
#pragma once
#include <string>

#include "core/config_fwd.hpp"
#include "field/hash_grid_config.hpp"
#include "field/kplanes_config.hpp"
#include "field/scene_flow_config.hpp"
#include "field/time_hash_grid_config.hpp"

namespace sgnlf::field {

struct Lidar4DEncoderConfig {
  KPlanesConfig planes;
  HashGridConfig static_hash = lidar4d_static_hash_config();
  TimeHashGridConfig time_hash;
  SceneFlowConfig flow;
  bool blend = true;  // false: the dynamic block is f(x, t) alone and the flow is unused

  void validate(const std::string& where = "lidar4d_encoder") const;  // throws ConfigError
  // Keys "planes", "static_hash", "time_hash", "flow" (objects), "blend"; unknown keys refused;
  // a key left out keeps LiDAR4D's value (static_hash's too: lidar4d_static_hash_config()).
  static Lidar4DEncoderConfig from_json(const Json& j, const std::string& where);
  Json to_json() const;  // every key, read back by from_json to the same config
};

}  // namespace sgnlf::field
