// LiDAR-NeRF (method.md §1): the neural LiDAR field trained on ground-truth poses.
#include "pipeline/methods/methods.hpp"

namespace sgnlf::pipeline::methods {

Method lidar_nerf() {
  Method m;
  m.name = "lidar-nerf";
  m.description = "LiDAR-NeRF with ground-truth poses (method.md §1)";
  m.preset_family = "lidar-nerf";
  m.implemented = true;
  m.compose = [](StepParts& p) -> StepPolicy& { return p.ground_truth_poses(); };
  return m;
}

}  // namespace sgnlf::pipeline::methods
