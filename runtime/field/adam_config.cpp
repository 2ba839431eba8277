// AdamConfig (adam_config.hpp): checks and JSON reading.
#include "field/adam_config.hpp"

#include "core/config.hpp"
#include "core/config_fields.hpp"

namespace sgnlf::field {

void AdamConfig::validate(const std::string& where) const { config::check_fields(*this, where); }

AdamConfig AdamConfig::from_json(ConfigReader& r) {
  AdamConfig c;
  config::read_fields_here(r, c);
  c.validate();
  return c;
}

}  // namespace sgnlf::field
