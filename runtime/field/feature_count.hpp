// The per-entry feature counts the field kernels are built for (1, 2, 4 or 8 floats: one
// vector load), checked once for every encoding's configuration.
#pragma once
#include <string>

#include "core/error.hpp"

namespace sgnlf::field {

// Throws ConfigError naming `where` and 'features' unless features is 1, 2, 4 or 8.
inline void check_feature_count(const std::string& where, int features) {
  if (features != 1 && features != 2 && features != 4 && features != 8)
    throw ConfigError(where + ": 'features' = " + std::to_string(features) +
                      " must be 1, 2, 4 or 8");
}

}  // namespace sgnlf::field
