// Lidar4DConfig (lidar4d_config.hpp).
#include "pipeline/config/lidar4d_config.hpp"

#include "core/config.hpp"
#include "core/config_fields.hpp"

namespace sgnlf::pipeline {

void Lidar4DConfig::validate(const std::string& where) const {
  encoder.validate(where + ".lidar4d.encoder");
  config::check_fields(*this, where + ".lidar4d");
  refine.unet.validate(where + ".lidar4d.refine.unet");
}

Lidar4DConfig Lidar4DConfig::from_json(ConfigReader& r) {
  Lidar4DConfig c;
  if (r.has("lidar4d")) config::read_fields(r, "lidar4d", c);
  return c;
}

void Lidar4DConfig::to_json(Json& j) const { j["lidar4d"] = config::write_fields(*this); }

}  // namespace sgnlf::pipeline
