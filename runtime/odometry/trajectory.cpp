// estimate_trajectory (see trajectory.hpp).
#include "odometry/trajectory.hpp"

#include <chrono>

#include "core/error.hpp"

namespace sgnlf::odometry {

Cloud to_cloud(const std::vector<PointXYZI>& points) {
  Cloud c;
  c.reserve(points.size());
  for (const auto& p : points) c.emplace_back(p.x, p.y, p.z);
  return c;
}

namespace {
TrajectoryResult run(const std::vector<const std::vector<PointXYZI>*>& scans,
                     const std::vector<double>& timestamps, LidarOdometry& odom,
                     const std::function<void(size_t, const FrameResult&)>& on_frame);
}  // namespace

TrajectoryResult estimate_trajectory(
    const std::vector<const std::vector<PointXYZI>*>& scans, const std::vector<double>& timestamps,
    const OdometryConfig& config, const std::function<void(size_t, const FrameResult&)>& on_frame) {
  LidarOdometry odom(config);
  return run(scans, timestamps, odom, on_frame);
}

TrajectoryResult estimate_trajectory(
    const std::vector<const std::vector<PointXYZI>*>& scans, const std::vector<double>& timestamps,
    const OdometryConfig& config, const Sensor& sensor,
    const std::function<void(size_t, const FrameResult&)>& on_frame) {
  LidarOdometry odom(config, sensor.sweep, sensor.sweep_duration_s());
  return run(scans, timestamps, odom, on_frame);
}

namespace {
TrajectoryResult run(const std::vector<const std::vector<PointXYZI>*>& scans,
                     const std::vector<double>& timestamps, LidarOdometry& odom,
                     const std::function<void(size_t, const FrameResult&)>& on_frame) {
  if (scans.size() != timestamps.size())
    throw Error("estimate_trajectory: " + std::to_string(scans.size()) + " scans but " +
                std::to_string(timestamps.size()) + " timestamps");
  TrajectoryResult r;
  const auto t0 = std::chrono::steady_clock::now();
  for (size_t k = 0; k < scans.size(); ++k) {
    FrameResult fr = odom.register_frame(to_cloud(*scans[k]), timestamps[k]);
    if (!fr.ok()) r.failed.push_back(int(k));
    r.T_world_lidar.push_back(fr.T_world_lidar);
    r.frames.push_back(std::move(fr));
    if (on_frame) on_frame(k, r.frames.back());
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}
}  // namespace

}  // namespace sgnlf::odometry
