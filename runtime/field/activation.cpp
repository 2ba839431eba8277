// Activation names (activation.hpp).
#include "field/activation.hpp"

#include "core/error.hpp"

namespace sgnlf::field {

Activation activation_from_string(const std::string& s) {
  for (const auto& [a, name] : kActivationNames)
    if (s == name) return a;
  throw ConfigError("activation '" + s + "' is not one of none, relu, tanh, softplus, sine");
}

std::string to_string(Activation a) {
  for (const auto& [value, name] : kActivationNames)
    if (value == a) return name;
  return "?";
}

}  // namespace sgnlf::field
