// The message of the ConfigError a call throws, or "" when it throws none (the config tests).
#pragma once
#include <functional>
#include <string>

#include "core/config.hpp"

namespace sgnlf::test {

inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace sgnlf::test
