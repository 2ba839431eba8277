// LiDAR4D (method.md §2): a row of the tables, not implemented in this build.
#include "pipeline/methods/methods.hpp"

namespace sgnlf::pipeline::methods {

Method lidar4d() {
  Method m;
  m.name = "lidar4d";
  m.description = "LiDAR4D with ground-truth poses (method.md §2)";
  m.preset_family = "lidar4d";
  return m;
}

}  // namespace sgnlf::pipeline::methods
