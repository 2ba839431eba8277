// KPlanesConfig (kplanes_config.hpp): checks and JSON reading.
#include "core/config_fields.hpp"
#include "field/kplanes_config.hpp"

#include <string>

#include "core/config.hpp"
#include "core/error.hpp"
#include "field/feature_count.hpp"

namespace sgnlf::field {

void KPlanesConfig::validate(const std::string& where) const {
  config::check_fields(*this, where);
  check_feature_count(where, features);
  if (!(init_lo <= init_hi))
    throw ConfigError(where + ": 'init_lo' = " + std::to_string(init_lo) + " exceeds 'init_hi' = " +
                      std::to_string(init_hi));
  const long finest = long(resolution) << (scales - 1);
  if (finest > 8192)
    throw ConfigError(where + ": 'resolution' · 2^('scales' − 1) = " + std::to_string(finest) +
                      " exceeds 8192");
}

KPlanesConfig KPlanesConfig::from_json(const Json& j, const std::string& where) {
  KPlanesConfig c;
  ConfigReader r(j, where);
  config::read_fields_here(r, c);
  r.finish();
  c.validate(where);
  return c;
}

Json KPlanesConfig::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::field
