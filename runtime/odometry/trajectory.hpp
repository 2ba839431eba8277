// The odometry over a whole sequence: T_world_lidar of every scan, the first at the identity,
// with each frame's registration result and the wall time (scans per second).
#pragma once
#include <functional>
#include <vector>

#include "geometry/range_image.hpp"
#include "geometry/sensor.hpp"
#include "odometry/lidar_odometry.hpp"

namespace sgnlf::odometry {

struct TrajectoryResult {
  std::vector<Pose> T_world_lidar;
  std::vector<FrameResult> frames;
  std::vector<int> failed;  // indices of frames whose registration failed
  double seconds = 0.0;     // wall time of the registrations (conversion included)
  double scans_per_second() const { return seconds > 0 ? double(frames.size()) / seconds : 0.0; }
};

Cloud to_cloud(const std::vector<PointXYZI>& points);

// `on_frame(k, result)` after each frame (progress). Timestamps non-decreasing, one per scan.
// Without a sensor, config.deskew is refused (the time model is the sensor's).
TrajectoryResult estimate_trajectory(
    const std::vector<const std::vector<PointXYZI>*>& scans, const std::vector<double>& timestamps,
    const OdometryConfig& config,
    const std::function<void(size_t, const FrameResult&)>& on_frame = {});
// The same for scans of `sensor` (its per-point time model and sweep duration deskew them).
TrajectoryResult estimate_trajectory(
    const std::vector<const std::vector<PointXYZI>*>& scans, const std::vector<double>& timestamps,
    const OdometryConfig& config, const Sensor& sensor,
    const std::function<void(size_t, const FrameResult&)>& on_frame = {});

}  // namespace sgnlf::odometry
