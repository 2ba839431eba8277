// Ψ's spec (psi_spec.hpp).
#include "spectral/psi_spec.hpp"

#include "core/error.hpp"

namespace sgnlf::spectral {

void PsiSpec::validate() const {
  check_range("spectral psi", "k", k, 1, 128);
  check_range("spectral psi", "width", width, 1, 128);
  check_range("spectral psi", "hidden", hidden, 1, 8);
  check_range("spectral psi", "bias_init", bias_init, 0.0, 100.0);
  check_range("spectral psi", "first_layer_scale", first_layer_scale, 1e-3, 1e3);
  if (activation == field::Activation::Relu || activation == field::Activation::None)
    throw ConfigError("spectral psi: activation must be smooth (tanh, softplus or sine), got " +
                      field::to_string(activation));
}

PsiSpec PsiSpec::from_json(const Json& j, const std::string& where) {
  PsiSpec s;
  ConfigReader r(j, where);
  std::string act = field::to_string(s.activation);
  r.get("k", s.k).get("width", s.width).get("hidden", s.hidden).get("activation", act);
  r.get("bias_init", s.bias_init).get("first_layer_scale", s.first_layer_scale);
  r.finish();
  s.activation = field::activation_from_string(act);
  s.validate();
  return s;
}

Json PsiSpec::to_json() const {
  return Json{{"k", k}, {"width", width}, {"hidden", hidden}, {"activation", field::to_string(activation)},
              {"bias_init", bias_init}, {"first_layer_scale", first_layer_scale}};
}

}  // namespace sgnlf::spectral
