// Ψ's spec (psi_spec.hpp).
#include "core/config_fields.hpp"
#include "spectral/psi_spec.hpp"

#include "core/config.hpp"
#include "core/error.hpp"

namespace sgnlf::spectral {

void PsiSpec::validate() const {
  config::check_fields(*this, "spectral psi");
  if (activation == field::Activation::Relu || activation == field::Activation::None)
    throw ConfigError("spectral psi: activation must be smooth (tanh, softplus or sine), got " +
                      field::to_string(activation));
}

PsiSpec PsiSpec::from_json(const Json& j, const std::string& where) {
  PsiSpec s;
  ConfigReader r(j, where);
  config::read_fields_here(r, s);
  r.finish();
  s.validate();
  return s;
}

Json PsiSpec::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::spectral
