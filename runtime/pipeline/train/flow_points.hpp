// The points LiDAR4D's flow supervision compares (method.md §2; LiDAR4D removes the ground
// before it fits the flow): per dataset frame, its returns split into ground and the rest, in
// the normalised world frame of the scene's poses, each part subsampled with a fixed seed.
// The ground is found from the scan itself, not from a mounting height: the densest height bin
// among the lower half of the returns near the sensor (the road is the largest flat surface
// below the sensor in a driving scan); a return below that height + margin is ground.
#pragma once
#include <cstdint>
#include <vector>

#include "datasets/dataset.hpp"
#include "geometry/kdtree.hpp"
#include "pipeline/config/lidar4d_config.hpp"
#include "pipeline/model/scene.hpp"

namespace sgnlf::pipeline {

struct FramePoints {
  std::vector<geometry::Point3f> moving;  // above the ground (normalised world frame)
  std::vector<geometry::Point3f> ground;  // the ground's returns (normalised world frame)
};

// Ground height (sensor frame z, metres) of a scan; throws sgnlf::Error naming `what` when no
// return lies within c.ground_range_m.
double ground_height(const std::vector<PointXYZI>& points, const FlowSupervisionConfig& c,
                     const std::string& what);

// One entry per dataset frame (scene.T_world_lidar's order): c.points moving and
// c.ground_points ground points at most, drawn without replacement from (seed, frame).
std::vector<FramePoints> flow_points(const Dataset& d, const Scene& scene,
                                     const FlowSupervisionConfig& c, uint64_t seed);

}  // namespace sgnlf::pipeline
