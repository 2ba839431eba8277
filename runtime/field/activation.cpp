// Activation names (activation.hpp).
#include "field/activation.hpp"

#include "core/error.hpp"

namespace sgnlf::field {

Activation activation_from_string(const std::string& s) {
  if (s == "none") return Activation::None;
  if (s == "relu") return Activation::Relu;
  if (s == "tanh") return Activation::Tanh;
  if (s == "softplus") return Activation::Softplus;
  if (s == "sine") return Activation::Sine;
  throw ConfigError("activation '" + s + "' is not one of none, relu, tanh, softplus, sine");
}

std::string to_string(Activation a) {
  switch (a) {
    case Activation::None: return "none";
    case Activation::Relu: return "relu";
    case Activation::Tanh: return "tanh";
    case Activation::Softplus: return "softplus";
    case Activation::Sine: return "sine";
  }
  return "?";
}

}  // namespace sgnlf::field
