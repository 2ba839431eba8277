// The LiDAR odometry front-end, composed of the modules of this folder in KISS-ICP's order
// (Vizzo et al., RA-L 2023, Alg. 1):
//   1. crop to [min_range, max_range]; downsample at 0.5 v (map points) and 1.5 v (source);
//   2. predict with constant velocity (motion_model.hpp);
//   3. (ours, for 2 Hz keyframes) a coarse ICP stage (from several planar starts while no
//      motion has been estimated yet, the best kept by its overlap with the fine map) on a coarser source against a coarse map
//      whose voxels are coarse_threshold / 2 wide, correspondences within
//      max(coarse_threshold, 3σ); then the KISS-ICP stage: the fine map, 3σ, κ = σ/3;
//   4. update σ from the model deviation (adaptive_threshold.hpp) and both maps.
// With config.deskew each scan is first deskewed (KISS-ICP §III-A, geometry/deskew.hpp) and,
// once registered, deskewed again with the refined velocity and registered once more.
// A frame whose registration fails (too few points, no overlap, low fitness, no convergence)
// keeps the predicted pose, is reported with converged = false, and does not enter the maps.
// The first frame (or any frame arriving while the map is empty) defines the map at its
// predicted pose (the identity for the first). Deterministic for a given input and config.
#pragma once
#include <vector>

#include "geometry/sweep_timing.hpp"
#include "odometry/adaptive_threshold.hpp"
#include "odometry/odometry_config.hpp"
#include "odometry/registration.hpp"
#include "odometry/voxel_map.hpp"

namespace sgnlf::odometry {

struct FrameResult {
  Pose T_world_lidar = Pose::Identity();
  Pose T_world_lidar_predicted = Pose::Identity();
  RegistrationResult registration;  // the final stage (iterations: both stages)
  bool initialised_map = false;     // this frame started the map (no registration)
  double sigma = 0.0;               // the adaptive threshold used (metres)
  size_t source_points = 0, map_points = 0;
  bool ok() const { return initialised_map || registration.converged; }
};

class LidarOdometry {
 public:
  // `sweep` and `sweep_duration_s` (the sensor's per-point time model, Sensor::sweep and
  // 1 / rate_hz) are used with config.deskew only, which needs a positive duration.
  explicit LidarOdometry(const OdometryConfig& config, const SweepTiming& sweep = {},
                         double sweep_duration_s = 0.0);

  // Registers a scan (sensor frame, metres) taken at `timestamp_s` (non-decreasing).
  FrameResult register_frame(const Cloud& scan_lidar, double timestamp_s);

  const std::vector<Pose>& poses() const { return poses_; }
  const VoxelHashMap& local_map() const { return map_; }
  const OdometryConfig& config() const { return cfg_; }

 private:
  static Cloud transformed(const Cloud& c, const Pose& T);
  // The scan deskewed with the constant velocity between two poses dt_s apart.
  Cloud deskewed(const Cloud& scan_lidar, const Pose& T_world_a, const Pose& T_world_b, double dt_s) const;

  OdometryConfig cfg_;
  SweepTiming sweep_;
  double sweep_duration_s_ = 0.0;
  VoxelHashMap map_, coarse_map_;
  AdaptiveThreshold threshold_;
  std::vector<Pose> poses_;
  std::vector<double> timestamps_;
  bool has_motion_ = false;  // a frame has registered since the map started (a velocity exists)
};

}  // namespace sgnlf::odometry
