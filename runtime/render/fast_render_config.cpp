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

FastRenderConfig FastRenderConfig::from_json(const Json& j, const std::string& where) {
  FastRenderConfig c;
  ConfigReader r(j, where);
  config::read_fields_here(r, c);
  r.finish();
  c.validate(where);
  return c;
}

Json FastRenderConfig::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::render
