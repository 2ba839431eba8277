// The naive baseline of `sgnlf eval`: no learning, the nearest training scan re-projected.
// For a test view, take the training scan whose ground-truth pose position is nearest to the
// test pose's, move its points with the ground-truth poses into the test LiDAR frame
// (p_test = inv(T_world_lidar_test) · T_world_lidar_train · p) and project them
// (project_points, protocol §1). ray_drop = 1 where a point landed (a certain "return"),
// intensity is carried over. It sets the floor every learned method should beat.
#pragma once
#include <vector>

#include "geometry/range_image.hpp"
#include "geometry/se3.hpp"
#include "geometry/sensor.hpp"

namespace sgnlf::metrics {

// Index of the training pose whose position is nearest to T_world_lidar_test's (first on ties).
size_t nearest_train_pose(const std::vector<Pose>& T_world_lidar_train,
                          const Pose& T_world_lidar_test);

RangeImage naive_baseline_view(const Sensor& sensor,
                               const std::vector<Pose>& T_world_lidar_train,
                               const std::vector<const std::vector<PointXYZI>*>& train_scans,
                               const Pose& T_world_lidar_test);

}  // namespace sgnlf::metrics
