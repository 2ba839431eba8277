// The trajectories of a pose-free run folder (T_world_lidar, the dataset's world frame, metres):
//   <run>/trajectories/{gt,initial,optimised}.kitti.txt   (12 numbers per line, frame order)
//   <run>/trajectories/{gt,initial,optimised}.tum.txt     (timestamp tx ty tz qx qy qz qw)
//   <run>/trajectories/top_view.svg  ground truth, initial and optimised poses from above, each
//                                    optimised pose joined to its ground truth (not aligned)
// Scans without reference poses (Dataset::has_reference_poses false) get no gt files, and the
// picture joins each optimised pose to its initial one.
#pragma once
#include <string>
#include <vector>

#include "datasets/dataset.hpp"

namespace sgnlf::pipeline {

// Returns the folder written.
std::string write_run_trajectories(const std::string& run_dir, const Dataset& d,
                                   const std::vector<Pose>& T_world_lidar_init,
                                   const std::vector<Pose>& T_world_lidar_optimised);

}  // namespace sgnlf::pipeline
