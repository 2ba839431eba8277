// Reading JSON of uncertain shape (result files hand-edited, truncated or from another tool):
// look-ups that give null instead of throwing.
#pragma once
#include <string>

#include "core/config_fwd.hpp"

namespace sgnlf {

// j[k] when j is an object holding k, else a null Json; never throws.
const Json& member_or_null(const Json& j, const std::string& k);

}  // namespace sgnlf
