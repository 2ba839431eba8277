// LiDAR4D (method.md §2): the ground-truth-pose step on the 4D field (the config's lidar4d
// section: K-Planes + hash grids with scene-flow blending, the Chamfer term, the networks'
// learning rate), with the scene-flow supervision around it.
#include "pipeline/methods/methods.hpp"

namespace sgnlf::pipeline::methods {

Method lidar4d() {
  Method m;
  m.name = "lidar4d";
  m.description = "LiDAR4D with ground-truth poses (method.md §2)";
  m.preset_family = "lidar4d";
  m.sections.lidar4d = true;
  m.implemented = true;
  m.compose = [](StepParts& p) -> StepPolicy& { return p.scene_flow(p.ground_truth_poses()); };
  return m;
}

}  // namespace sgnlf::pipeline::methods
