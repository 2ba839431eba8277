// member_or_null (see json_lookup.hpp).
#include "core/json_lookup.hpp"

#include "core/config.hpp"

namespace sgnlf {

const Json& member_or_null(const Json& j, const std::string& k) {
  static const Json null_json;
  return j.is_object() && j.contains(k) ? j[k] : null_json;
}

}  // namespace sgnlf
