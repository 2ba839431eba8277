// Control row (not in the paper): GeoNLF's field trained on the frozen initial poses.
#include "core/config.hpp"
#include "pipeline/methods/methods.hpp"

namespace sgnlf::pipeline::methods {

Method geonlf_frozen() {
  Method m = geonlf();
  m.name = "geonlf-frozen";
  m.description =
      "control (not in the paper): GeoNLF's field trained on the frozen initial poses";
  m.overrides = Json{{"method", m.name},
                     {"pose_optim", {{"optimize", false}}},
                     {"geometric", nullptr}};  // no geometric stage
  return m;
}

}  // namespace sgnlf::pipeline::methods
