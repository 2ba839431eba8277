// Ψ's architecture and initialisation, the config's "spectral"."psi" (method.md §4.1). Host-only
// config; the network itself is spectral/psi.hpp (psi_mlp_spec, init_psi_params).
#pragma once
#include <string>

#include "core/config.hpp"
#include "field/activation.hpp"

namespace sgnlf::spectral {

struct PsiSpec {
  int k = 16;       // eigenfunctions
  int width = 64;   // hidden width
  int hidden = 2;   // hidden layers
  field::Activation activation = field::Activation::Tanh;  // smooth: tanh, softplus or sine
  // Initialisation on top of the field's fan-in init: hidden biases U(±bias_init) (zero biases
  // make a tanh/sine network odd in x at the start), first-layer weights × first_layer_scale
  // (the frequency content of the first features, SIREN's ω0).
  double bias_init = 1.0;
  double first_layer_scale = 1.0;
  void validate() const;
  static PsiSpec from_json(const Json& j, const std::string& where);
  Json to_json() const;
};

}  // namespace sgnlf::spectral
