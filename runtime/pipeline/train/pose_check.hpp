// The end-of-run convergence check of a pose-free run (posegraph/trajectory_check.hpp) on the
// dataset's own scans: 4000 points a frame (seed 1), edges (i, i+1). Written into summary.json
// and metrics.json as "trajectory_check" and warned about when the poses did not converge.
#pragma once
#include <vector>

#include "datasets/dataset.hpp"
#include "posegraph/trajectory_check.hpp"

namespace sgnlf::pipeline {

posegraph::TrajectoryCheck check_run_poses(const Dataset& d,
                                           const std::vector<Pose>& T_world_lidar);

}  // namespace sgnlf::pipeline
