// The scene's point cloud: every frame's points (the returns inside the sensor's range, as
// loaded) moved into the world frame by its pose, in frame order, intensity kept.
#pragma once
#include <vector>

#include "datasets/dataset.hpp"

namespace sgnlf::workflow {

// `T_world_lidar`: one pose per frame of `d` (Error otherwise). `voxel_m` > 0 keeps the first
// point of each voxel of that size (in frame order); 0 keeps every point.
std::vector<PointXYZI> scene_cloud(const Dataset& d, const std::vector<Pose>& T_world_lidar,
                                   double voxel_m = 0.0);

}  // namespace sgnlf::workflow
