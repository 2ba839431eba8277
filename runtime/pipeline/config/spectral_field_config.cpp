// SpectralFieldConfig (spectral_field_config.hpp).
#include "pipeline/config/spectral_field_config.hpp"

#include <cmath>

#include "core/config.hpp"
#include "core/config_fields.hpp"
#include "core/error.hpp"

namespace sgnlf::pipeline {

void SpectralFieldConfig::validate(const std::string& where) const {
  psi.validate();
  loss.validate();
  fusion.validate();
  config::check_fields(*this, where + ".spectral");
}

SpectralFieldConfig SpectralFieldConfig::from_json(ConfigReader& r) {
  SpectralFieldConfig c;
  ConfigReader s = r.child("spectral");
  config::refuse_enabled_key(s, "spectral");
  config::read_fields_here(s, c);
  s.finish();
  return c;
}

void SpectralFieldConfig::to_json(Json& j) const { j["spectral"] = config::write_fields(*this); }

double SpectralFieldConfig::lr_at(long step, long iterations) const {
  const double t = iterations > 1 ? std::min(1.0, double(step) / double(iterations - 1)) : 1.0;
  return lr * (lr_final + (1.0 - lr_final) * 0.5 * (1.0 + std::cos(3.141592653589793 * t)));
}

}  // namespace sgnlf::pipeline
