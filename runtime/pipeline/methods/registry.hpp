// The method registry: every method of this folder, in table order. The only place that looks a
// method up by its name.
#pragma once
#include <string>
#include <vector>

#include "pipeline/methods/method.hpp"

namespace sgnlf::pipeline {

const std::vector<Method>& method_registry();
// ConfigError naming the known methods when `name` is not one.
const Method& find_method(const std::string& name);

}  // namespace sgnlf::pipeline
