// KPlanesConfig (kplanes_config.hpp): checks and JSON reading.
#include "field/kplanes_config.hpp"

#include <string>

#include "core/error.hpp"

namespace sgnlf::field {

void KPlanesConfig::validate(const std::string& where) const {
  config::check_fields(*this, where);
  if (features != 1 && features != 2 && features != 4 && features != 8)
    throw ConfigError(where + ": 'features' = " + std::to_string(features) +
                      " must be 1, 2, 4 or 8");
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

}  // namespace sgnlf::field
