// HashGridConfig (hash_grid_config.hpp): checks and JSON reading.
#include "field/hash_grid_config.hpp"

#include <cmath>
#include <string>

#include "core/config.hpp"
#include "core/config_fields.hpp"
#include "core/error.hpp"
#include "field/feature_count.hpp"

namespace sgnlf::field {

void HashGridConfig::validate(const std::string& w) const {
  check_range(w, "levels", levels, 1, 32);
  check_feature_count(w, features);
  check_range(w, "log2_table_size", log2_table_size, 4, 24);
  check_range(w, "base_resolution", base_resolution, 1.0f, 8192.0f);
  check_range(w, "per_level_scale", per_level_scale, 1.0f, 4.0f);
  if (schedule != "auto" && schedule != "chunked" && schedule != "per_point")
    throw ConfigError(w + ": 'schedule' = '" + schedule + "' is not auto, chunked or per_point");
  const double finest = base_resolution * std::pow(double(per_level_scale), levels - 1);
  if (finest > 1.0e6)
    throw ConfigError(w + ": finest resolution " + std::to_string(finest) + " exceeds 1e6");
}

void HashGridConfig::read_keys(ConfigReader& r) { config::read_fields_here(r, *this); }

HashGridConfig HashGridConfig::from_json(ConfigReader& r) {
  HashGridConfig c;
  c.read_keys(r);
  c.validate();
  return c;
}

HashGridConfig lidar4d_static_hash_config() {
  HashGridConfig c;
  c.levels = 8;
  c.features = 4;
  c.log2_table_size = 19;
  c.base_resolution = 512.0f;
  c.per_level_scale = float(std::exp2(std::log2(32768.0 / 512.0) / 7.0));
  return c;
}

}  // namespace sgnlf::field
