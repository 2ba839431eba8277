// TimeHashGridConfig (time_hash_grid_config.hpp): checks and JSON reading.
#include "core/config_fields.hpp"
#include "field/time_hash_grid_config.hpp"

#include <cmath>
#include <string>

#include "core/config.hpp"
#include "core/error.hpp"
#include "field/feature_count.hpp"

namespace sgnlf::field {

void TimeHashGridConfig::validate(const std::string& where) const {
  config::check_fields(*this, where);
  check_feature_count(where, features);
  const double finest = base_resolution * std::pow(double(per_level_scale), levels - 1);
  if (finest > 1.0e6)
    throw ConfigError(where + ": finest resolution " + std::to_string(finest) +
                      " ('base_resolution' · 'per_level_scale'^('levels' − 1)) exceeds 1e6");
}

TimeHashGridConfig TimeHashGridConfig::from_json(const Json& j, const std::string& where) {
  TimeHashGridConfig c;
  ConfigReader r(j, where);
  config::read_fields_here(r, c);
  r.finish();
  c.validate(where);
  return c;
}

Json TimeHashGridConfig::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::field
