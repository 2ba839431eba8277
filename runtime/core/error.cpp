#include "core/error.hpp"

namespace sgnlf {
void require(bool cond, const std::string& what) {
  if (!cond) throw Error(what);
}
}  // namespace sgnlf
