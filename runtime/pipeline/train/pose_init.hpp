// Initial poses of a pose-free run (protocol §3), in the dataset's world frame (metres):
// "gt" (ground truth), "noisy" (T_gt · Exp(ξ), ω ~ N(0, σ_rot²), u ~ N(0, σ_trans²) per axis,
// right-multiplied, seed from the config, no frame fixed), "identity", or "odometry" (the built-in
// LiDAR odometry on the scans, odometry/lidar_odometry.hpp, first frame at the identity).
// Deterministic, so a run folder recomputes them from its config instead of storing them.
#pragma once
#include <vector>

#include "datasets/dataset.hpp"
#include "pipeline/config/pose_free_config.hpp"

namespace sgnlf::pipeline {

std::vector<Pose> initial_poses(const Dataset& d, const PoseInitConfig& c);

}  // namespace sgnlf::pipeline
