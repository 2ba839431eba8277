// Lidar4DConfig (lidar4d_config.hpp).
#include "pipeline/config/lidar4d_config.hpp"

#include "core/config.hpp"
#include "core/config_fields.hpp"

namespace sgnlf::pipeline {

void Lidar4DConfig::validate(const std::string& where) const {
  encoder.validate(where + ".lidar4d.encoder");
  config::check_fields(*this, where + ".lidar4d");
  if (refine) refine->unet.validate(where + ".lidar4d.refine.unet");
}

Lidar4DConfig Lidar4DConfig::from_json(ConfigReader& r) {
  Lidar4DConfig c;
  ConfigReader s = r.child("lidar4d");
  config::refuse_enabled_key(s, "lidar4d");
  config::read_fields_here(s, c);
  s.finish();
  return c;
}

void Lidar4DConfig::to_json(Json& j) const { j["lidar4d"] = config::write_fields(*this); }

}  // namespace sgnlf::pipeline
