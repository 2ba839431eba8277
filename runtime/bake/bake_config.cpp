// BakeConfig validation and JSON.
#include "bake/bake_config.hpp"

#include "core/config.hpp"
#include "core/config_fields.hpp"

namespace sgnlf::bake {

void BakeConfig::validate(const std::string& where) const {
  config::check_fields(*this, where);
  if (step_m > 0.0f && step_m > voxel_m)
    throw ConfigError(where + ": 'step_m' = " + std::to_string(step_m) +
                      " is coarser than 'voxel_m' = " + std::to_string(voxel_m) +
                      " (samples would skip voxels)");
}

BakeConfig BakeConfig::from_json(const Json& j, const std::string& where, const BakeConfig& base) {
  BakeConfig c = base;
  ConfigReader r(j, where);
  config::read_fields_here(r, c);
  r.finish();
  c.validate(where);
  return c;
}

BakeConfig BakeConfig::from_json(const Json& j, const std::string& where) {
  return from_json(j, where, BakeConfig{});
}

Json BakeConfig::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::bake
