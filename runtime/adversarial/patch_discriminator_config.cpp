// PatchDiscriminatorConfig (patch_discriminator_config.hpp).
#include "adversarial/patch_discriminator_config.hpp"

#include "core/config.hpp"
#include "core/config_fields.hpp"
#include "core/error.hpp"

namespace sgnlf::adversarial {

void PatchDiscriminatorConfig::validate(const std::string& where) const {
  config::check_fields(*this, where);
  if (channels.empty() || channels.size() > 6)
    throw ConfigError(where + ": 'channels' has " + std::to_string(channels.size()) +
                      " layers, expected 1 to 6");
  if (strides.size() != channels.size())
    throw ConfigError(where + ": 'strides' has " + std::to_string(strides.size()) +
                      " entries, 'channels' has " + std::to_string(channels.size()));
  for (size_t l = 0; l < channels.size(); ++l) {
    check_range(where, "channels[" + std::to_string(l) + "]", channels[l], 1, 512);
    check_range(where, "strides[" + std::to_string(l) + "]", strides[l], 1, 2);
  }
  check_range(where, "padding", padding, 0, kernel - 1);
}

PatchDiscriminatorConfig PatchDiscriminatorConfig::from_json(const Json& section,
                                                             const std::string& where) {
  PatchDiscriminatorConfig c;
  ConfigReader r(section, where);  // refuses a section that is not an object
  config::read_fields_here(r, c);  // the layer lists: integers only
  r.finish();
  c.validate(where);
  return c;
}

Json PatchDiscriminatorConfig::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::adversarial
