// Lidar4DEncoderConfig (lidar4d_encoder_config.hpp): checks and JSON reading and writing.
#include "field/lidar4d_encoder_config.hpp"

#include <string>

#include "core/config.hpp"
#include "core/config_fields.hpp"
#include "core/error.hpp"

namespace sgnlf::field {

void Lidar4DEncoderConfig::validate(const std::string& where) const {
  planes.validate(where + ".planes");
  static_hash.validate(where + ".static_hash");
  time_hash.validate(where + ".time_hash");
  flow.validate(where + ".flow");
}

Lidar4DEncoderConfig Lidar4DEncoderConfig::from_json(const Json& j, const std::string& where) {
  Lidar4DEncoderConfig c;
  ConfigReader r(j, where);
  if (r.has("planes")) {
    ConfigReader s = r.child("planes");
    config::read_fields_here(s, c.planes);
    s.finish();
  }
  if (r.has("static_hash")) {
    ConfigReader s = r.child("static_hash");
    c.static_hash.read_keys(s);  // keys left out keep LiDAR4D's values
    s.finish();
  }
  if (r.has("time_hash")) {
    ConfigReader s = r.child("time_hash");
    config::read_fields_here(s, c.time_hash);
    s.finish();
  }
  if (r.has("flow")) {
    ConfigReader s = r.child("flow");
    config::read_fields_here(s, c.flow);
    s.finish();
  }
  r.get("blend", c.blend);
  r.finish();
  c.validate(where);
  return c;
}

Json Lidar4DEncoderConfig::to_json() const {
  return Json{{"planes", planes.to_json()},
              {"static_hash", config::write_fields(static_hash)},
              {"time_hash", time_hash.to_json()},
              {"flow", flow.to_json()},
              {"blend", blend}};
}

}  // namespace sgnlf::field
