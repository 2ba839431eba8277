// Nearest-scan re-projection baseline (see naive_baseline.hpp).
#include "metrics/naive_baseline.hpp"

#include <limits>
#include <string>

#include "core/error.hpp"

namespace sgnlf::metrics {

size_t nearest_train_pose(const std::vector<Pose>& T_world_lidar_train,
                          const Pose& T_world_lidar_test) {
  require(!T_world_lidar_train.empty(), "naive baseline: no training poses");
  require(T_world_lidar_test.matrix().allFinite(), "naive baseline: test pose is not finite");
  size_t best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < T_world_lidar_train.size(); ++k) {
    require(T_world_lidar_train[k].matrix().allFinite(),
            "naive baseline: training pose " + std::to_string(k) + " is not finite");
    const double d =
        (T_world_lidar_train[k].translation() - T_world_lidar_test.translation()).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = k;
    }
  }
  return best;
}

RangeImage naive_baseline_view(const Sensor& sensor,
                               const std::vector<Pose>& T_world_lidar_train,
                               const std::vector<const std::vector<PointXYZI>*>& train_scans,
                               const Pose& T_world_lidar_test) {
  require(T_world_lidar_train.size() == train_scans.size(),
          "naive baseline: " + std::to_string(T_world_lidar_train.size()) +
              " training poses vs " + std::to_string(train_scans.size()) + " training scans");
  const size_t k = nearest_train_pose(T_world_lidar_train, T_world_lidar_test);
  require(train_scans[k] != nullptr,
          "naive baseline: training scan " + std::to_string(k) + " is null");
  const Pose T_test_train = T_world_lidar_test.inverse() * T_world_lidar_train[k];
  const std::vector<PointXYZI>& scan = *train_scans[k];
  std::vector<PointXYZI> moved(scan.size());
  for (size_t i = 0; i < scan.size(); ++i) {
    const Vec3 p = T_test_train * Vec3(scan[i].x, scan[i].y, scan[i].z);
    moved[i] = {float(p.x()), float(p.y()), float(p.z()), scan[i].intensity};
  }
  // project_points drops non-finite points and counts them; the label it writes (1 where a
  // point landed) is the baseline's return probability.
  return project_points(sensor, moved);
}

}  // namespace sgnlf::metrics
