// The activations of the field's MLPs (field/mlp.hpp) and their names in configs. Host-only, so
// that configs naming an activation (spectral::PsiSpec) parse without the OpenCL layer.
#pragma once
#include <string>
#include <utility>

namespace sgnlf::field {

enum class Activation { None = 0, Relu = 1, Tanh = 2, Softplus = 3, Sine = 4 };
// The names, once (config::choices(kActivationNames) in a config's field list).
inline constexpr std::pair<Activation, const char*> kActivationNames[] = {
    {Activation::None, "none"},
    {Activation::Relu, "relu"},
    {Activation::Tanh, "tanh"},
    {Activation::Softplus, "softplus"},
    {Activation::Sine, "sine"}};
Activation activation_from_string(const std::string& s);  // "none", "relu", ...; ConfigError
std::string to_string(Activation a);

}  // namespace sgnlf::field
