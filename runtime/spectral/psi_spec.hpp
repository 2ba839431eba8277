// Ψ's architecture and initialisation, the config's "spectral"."psi" (method.md §4.1). Host-only
// config; the network itself is spectral/psi.hpp (psi_mlp_spec, init_psi_params).
#pragma once
#include <string>

#include "core/config_choices.hpp"
#include "core/config_fwd.hpp"
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
  // The keys and ranges (core/config_fields.hpp); that the activation is smooth is validate()'s.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("k", s.k, 1, 128);
    v("width", s.width, 1, 128);
    v("hidden", s.hidden, 1, 8);
    v("activation", s.activation, config::choices(field::kActivationNames));
    v("bias_init", s.bias_init, 0.0, 100.0);
    v("first_layer_scale", s.first_layer_scale, 1e-3, 1e3);
  }
  void validate() const;
  static PsiSpec from_json(const Json& j, const std::string& where);
  Json to_json() const;
};

}  // namespace sgnlf::spectral
