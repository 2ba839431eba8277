// FastRenderConfig validation and JSON.
#include "core/config_fields.hpp"
#include "render/fast_render_config.hpp"

#include "core/config.hpp"

namespace sgnlf::render {

void FastRenderConfig::validate(const std::string& where) const {
  config::check_fields(*this, where);
  if (layout != "protocol" && layout != "march")
    throw ConfigError(where + ": 'layout' = '" + layout + "' (expected \"protocol\" or \"march\")");
}

FastRenderConfig FastRenderConfig::march() {
  FastRenderConfig c;
  c.layout = "march";
  c.refine = 4;
  c.hit_alpha = 1e-2f;
  c.coarse = 2;
  c.stop_transmittance = 1e-3f;
  c.head_weight_threshold = 1e-3f;
  c.wave = 8;
  return c;
}

FastRenderConfig FastRenderConfig::from_json(const Json& j, const std::string& where,
                                             const FastRenderConfig& base) {
  FastRenderConfig c = base;
  ConfigReader r(j, where);
  config::read_fields_here(r, c);
  r.finish();
  c.validate(where);
  return c;
}

FastRenderConfig FastRenderConfig::from_json(const Json& j, const std::string& where) {
  return from_json(j, where, FastRenderConfig{});
}

Json FastRenderConfig::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::render
