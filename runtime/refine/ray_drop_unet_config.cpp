// RayDropUNetConfig (ray_drop_unet_config.hpp).
#include "core/config_fields.hpp"
#include "refine/ray_drop_unet_config.hpp"

#include "core/config.hpp"
#include "core/error.hpp"

namespace sgnlf::refine {

void RayDropUNetConfig::validate(const std::string& where) const {
  config::check_fields(*this, where);
  if (channels % 16 != 0)
    throw ConfigError(where + ": 'channels' = " + std::to_string(channels) +
                      " is not a multiple of 16");
  // The widest layer, channels · 2^(depth − 1) · 2 at the deepest concatenation, stays within
  // the conv stack's 1024 channels.
  const long widest = long(channels) << depth;
  if (widest > 1024)
    throw ConfigError(where + ": 'channels' = " + std::to_string(channels) + " with 'depth' = " +
                      std::to_string(depth) + " makes a " + std::to_string(widest) +
                      "-channel concatenation; at most 1024");
  if (schedule == LrSchedule::one_cycle && (pct_start <= 0.0f || pct_start >= 1.0f))
    throw ConfigError(where + ": 'pct_start' = " + std::to_string(pct_start) +
                      " must lie strictly inside (0, 1) for the one_cycle schedule");
}

RayDropUNetConfig RayDropUNetConfig::from_json(const Json& section, const std::string& where) {
  RayDropUNetConfig c;
  ConfigReader r(section, where);  // refuses a section that is not an object
  config::read_fields_here(r, c);
  r.finish();
  c.validate(where);
  return c;
}

Json RayDropUNetConfig::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::refine
