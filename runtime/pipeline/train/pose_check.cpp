// check_run_poses (see pose_check.hpp).
#include "pipeline/train/pose_check.hpp"

#include "core/error.hpp"

namespace sgnlf::pipeline {

posegraph::TrajectoryCheck check_run_poses(const Dataset& d,
                                           const std::vector<Pose>& T_world_lidar) {
  require(d.frames.size() >= 2, "check_run_poses: " + d.name + " has fewer than 2 frames");
  std::vector<std::vector<PointXYZI>> scans;
  for (const auto& f : d.frames) scans.push_back(f.points);
  const auto clouds = posegraph::make_frame_clouds(scans, 4000, 1);
  return posegraph::check_trajectory(clouds, T_world_lidar,
                                     posegraph::sequential_edges(int(d.frames.size()), {1}));
}

}  // namespace sgnlf::pipeline
