// SpectralTrainConfig (spectral_train_config.hpp).
#include "core/config_fields.hpp"
#include "spectral/spectral_train_config.hpp"

#include "core/config.hpp"

namespace sgnlf::spectral {

void SpectralTrainConfig::validate() const {
  psi.validate();
  loss.validate();
  config::check_fields(*this, "spectral train");
}

SpectralTrainConfig SpectralTrainConfig::from_json(const Json& j, const std::string& where) {
  SpectralTrainConfig c;
  ConfigReader r(j, where);
  config::read_fields_here(r, c);
  r.finish();
  c.validate();
  return c;
}

Json SpectralTrainConfig::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::spectral
