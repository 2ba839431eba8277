// The odometry on simulated sequences at 10 Hz (HDL-64E) and 2 Hz (HDL-64E and HDL-32E
// keyframes metres and up to 15° apart; the first 16–20 frames, to keep the test short): every
// frame registers and the ATE (protocol §4,
// SE(3) Umeyama) stays below the stated bound. Also determinism: two runs give the same poses.
#include <catch2/catch.hpp>

#include "datasets/protocol.hpp"
#include "metrics/pose_errors.hpp"
#include "scans.hpp"

using namespace sgnlf;
using namespace sgnlf::odometry;

namespace {

TrajectoryResult run(const Dataset& d, const OdometryConfig& c = {}) {
  std::vector<const std::vector<PointXYZI>*> scans;
  std::vector<double> t;
  for (const auto& f : d.frames) {
    scans.push_back(&f.points);
    t.push_back(f.timestamp_s);
  }
  return estimate_trajectory(scans, t, c);
}

void check_sequence(const Dataset& d, double ate_bound_m) {
  const TrajectoryResult r = run(d);
  const auto e = metrics::compute_pose_errors(r.T_world_lidar, gt_poses(d));
  INFO(d.name << ": ATE " << e.ate_m << " m, RPE " << e.rpe_t_cm << " cm " << e.rpe_r_deg
              << " deg, failed frames " << r.failed.size());
  CHECK(r.failed.empty());
  CHECK(r.T_world_lidar.front().isApprox(Pose::Identity()));
  CHECK(e.ate_m < ate_bound_m);
}

}  // namespace

TEST_CASE("odometry on a 10 Hz HDL-64E sequence", "[odometry]") {
  check_sequence(test::simulated("kitti360-1538", 20), 0.10);
}

TEST_CASE("odometry on 2 Hz HDL-64E keyframes", "[odometry]") {
  check_sequence(test::kitti360_low(), 0.15);
}

TEST_CASE("odometry on 2 Hz HDL-32E keyframes", "[odometry]") {
  check_sequence(test::nuscenes_low(), 0.15);
}

TEST_CASE("odometry is deterministic, also with two threads", "[odometry]") {
  Dataset d = test::nuscenes_low();
  d.frames.resize(8);
  OdometryConfig two;
  two.threads = 2;
  const auto a = run(d), b = run(d), c = run(d, two), e = run(d, two);
  for (size_t k = 0; k < a.T_world_lidar.size(); ++k) {
    CHECK(a.T_world_lidar[k].matrix() == b.T_world_lidar[k].matrix());
    CHECK(c.T_world_lidar[k].matrix() == e.T_world_lidar[k].matrix());
  }
}

TEST_CASE("probing the start search keeps the exhaustive search's choice", "[odometry]") {
  // kitti360-low's second frame is the one that needs the planar start search (docs/studies/odometry
  // README: 2.36 m ATE without it). Probing each start with a few coarse iterations must keep
  // the start the exhaustive search keeps, and end at the same pose within a centimetre.
  Dataset d = test::kitti360_low();
  d.frames.resize(4);
  OdometryConfig exhaustive;
  exhaustive.initial_search_iterations = 0;
  const TrajectoryResult a = run(d), b = run(d, exhaustive);
  REQUIRE(a.failed.empty());
  REQUIRE(b.failed.empty());
  for (size_t k = 0; k < a.T_world_lidar.size(); ++k) {
    INFO("frame " << k);
    CHECK((a.T_world_lidar[k].translation() - b.T_world_lidar[k].translation()).norm() < 0.01);
  }
  const auto e = metrics::compute_pose_errors(a.T_world_lidar, gt_poses(d));
  CHECK(e.ate_m < 0.15);
}
