// Deskewing in the odometry (config 'deskew', geometry/deskew.hpp) on the distorted real-like
// twin: with the sensor's time model the trajectory ends closer to the ground truth than
// without; without a sensor (no time model) the option is refused; off, nothing changes.
#include <catch2/catch.hpp>

#include "datasets/protocol.hpp"
#include "metrics/pose_errors.hpp"
#include "scans.hpp"

using namespace sgnlf;
using namespace sgnlf::odometry;

namespace {

// All 36 keyframes (0.046 m without, 0.036 m with; deskewed with the true motion instead:
// 0.030 m). A 16-frame window is another street (its length follows the frame count) and too
// short: 0.037 m without, 0.046 m with, 0.019 m with the true motion; the velocity estimated
// from the first keyframes, 0.5 s apart, is not good enough there.
const Dataset& real_like() {
  static const Dataset d = test::simulated("nuscenes-real-like-a", 36);
  return d;
}

TrajectoryResult run(const Dataset& d, const OdometryConfig& c) {
  std::vector<const std::vector<PointXYZI>*> scans;
  std::vector<double> t;
  for (const auto& f : d.frames) {
    scans.push_back(&f.points);
    t.push_back(f.timestamp_s);
  }
  return estimate_trajectory(scans, t, c, d.sensor);
}

}  // namespace

TEST_CASE("deskewing lowers the odometry's ATE on the distorted twin", "[odometry][deskew]") {
  const Dataset& d = real_like();
  OdometryConfig off, on;
  on.deskew = true;
  const TrajectoryResult a = run(d, off), b = run(d, on);
  const auto gt = gt_poses(d);
  const auto ea = metrics::compute_pose_errors(a.T_world_lidar, gt);
  const auto eb = metrics::compute_pose_errors(b.T_world_lidar, gt);
  INFO("ATE without deskew " << ea.ate_m << " m (RPE " << ea.rpe_t_cm << " cm), with " << eb.ate_m << " m (RPE "
                             << eb.rpe_t_cm << " cm)");
  CHECK(a.failed.empty());
  CHECK(b.failed.empty());
  CHECK(eb.ate_m < ea.ate_m);
  CHECK(eb.rpe_t_cm < ea.rpe_t_cm);
}

TEST_CASE("deskew needs the sensor's time model", "[odometry][deskew]") {
  Dataset d = real_like();
  d.frames.resize(3);
  OdometryConfig on;
  on.deskew = true;
  std::vector<const std::vector<PointXYZI>*> scans;
  std::vector<double> t;
  for (const auto& f : d.frames) {
    scans.push_back(&f.points);
    t.push_back(f.timestamp_s);
  }
  CHECK_THROWS_WITH(estimate_trajectory(scans, t, on), Catch::Contains("deskew"));
  // Off, the sensor overload gives the poses of the plain one bit for bit.
  const auto x = estimate_trajectory(scans, t, OdometryConfig{}), y = run(d, OdometryConfig{});
  for (size_t k = 0; k < x.T_world_lidar.size(); ++k) CHECK(x.T_world_lidar[k].matrix() == y.T_world_lidar[k].matrix());
}
