// Registration of a scan against a perturbed copy of itself (small_gicp's test pattern: a
// known pose, fixed seed, errors asserted in metres and degrees) through the odometry's full
// path (coarse stage, then KISS-ICP's 3σ stage) at magnitudes up to 2 m and 15°: about random
// axes on an HDL-64E scan; vehicle-like (yaw, roll and pitch ~5 % of it, translation mostly
// horizontal) on an HDL-32E scan, whose 32 rings 1.3° apart made point-to-point ICP settle one
// ring spacing off for large roll or pitch before the planar start search existed (see
// docs/studies/odometry/README.md, "Ring aliasing"); and the failures that must be reported as such: too few points, no
// overlap, an empty map.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/rng.hpp"
#include "odometry/lidar_odometry.hpp"
#include "scans.hpp"

using namespace sgnlf;
using namespace sgnlf::odometry;

namespace {

constexpr double kDeg = M_PI / 180.0;

Vec3 random_unit(Rng& rng) {
  Vec3 v;
  for (int a = 0; a < 3; ++a) v[a] = rng.normal();  // sequenced: the same draws on every compiler
  return v.normalized();
}

Cloud transformed(const Cloud& c, const Pose& T) {
  Cloud out;
  for (const auto& p : c) out.push_back(T * p);
  return out;
}

struct PoseError {
  double trans_m, rot_deg;
};

PoseError pose_error(const Pose& est, const Pose& truth) {
  const Pose E = est.inverse() * truth;
  return {E.translation().norm(), rotation_angle(E.linear()) / kDeg};
}

// Registers `scan` as frame 0 and its perturbed copy as frame 1; returns frame 1's result.
FrameResult register_copy(const Cloud& scan, const Pose& T_world_copy) {
  LidarOdometry odom(OdometryConfig{});
  const FrameResult first = odom.register_frame(scan, 0.0);
  REQUIRE(first.initialised_map);
  return odom.register_frame(transformed(scan, T_world_copy.inverse()), 0.5);
}

void check_recovery(const Cloud& scan, uint64_t seed, bool vehicle_like) {
  Rng rng(seed);
  const double magnitudes[][2] = {{0.1, 1.0}, {0.5, 5.0}, {1.0, 10.0}, {2.0, 15.0}};
  for (const auto& m : magnitudes) {
    for (int trial = 0; trial < 3; ++trial) {
      Pose T = Pose::Identity();
      if (vehicle_like) {
        const double sign = rng.normal() < 0 ? -1.0 : 1.0;
        Vec3 axis(0, 0, sign), dir;
        axis.x() = 0.05 * rng.normal();
        axis.y() = 0.05 * rng.normal();
        for (int a = 0; a < 3; ++a) dir[a] = rng.normal() * (a == 2 ? 0.05 : 1.0);
        dir.normalize();
        T.linear() = exp_so3(axis * m[1] * kDeg);
        T.translation() = dir * m[0];
      } else {
        T.linear() = exp_so3(random_unit(rng) * m[1] * kDeg);
        T.translation() = random_unit(rng) * m[0];
      }
      const FrameResult fr = register_copy(scan, T);
      const PoseError e = pose_error(fr.T_world_lidar, T);
      INFO("perturbation " << m[0] << " m, " << m[1] << " deg, trial " << trial << ": error "
                           << e.trans_m << " m, " << e.rot_deg << " deg, iterations "
                           << fr.registration.iterations << ", fitness " << fr.registration.fitness
                           << ", failure '" << fr.registration.failure << "'");
      CHECK(fr.registration.converged);
      CHECK(fr.registration.iterations > 0);
      CHECK(fr.registration.fitness > 0.9);
      CHECK(e.trans_m < 0.05);
      CHECK(e.rot_deg < 0.2);
    }
  }
}

}  // namespace

TEST_CASE("a scan registers to a perturbed copy of itself (HDL-64E)", "[odometry]") {
  check_recovery(to_cloud(test::kitti360_low().frames[0].points), 11, false);
}

TEST_CASE("a scan registers to a perturbed copy of itself (HDL-32E, vehicle-like)", "[odometry]") {
  check_recovery(to_cloud(test::nuscenes_low().frames[0].points), 12, true);
}

TEST_CASE("too few points is a failure, not a converged pose", "[odometry]") {
  const Cloud scan = to_cloud(test::kitti360_low().frames[0].points);
  LidarOdometry odom(OdometryConfig{});
  odom.register_frame(scan, 0.0);
  const size_t map_before = odom.local_map().num_points();
  Cloud few(scan.begin(), scan.begin() + 40);
  const FrameResult fr = odom.register_frame(few, 0.5);
  CHECK_FALSE(fr.ok());
  CHECK_FALSE(fr.registration.converged);
  CHECK(fr.registration.failure.find("too few points") != std::string::npos);
  CHECK(odom.local_map().num_points() == map_before);  // a failed frame does not enter the map
}

TEST_CASE("a scan with no overlap is a failure, not a converged pose", "[odometry]") {
  const Cloud scan = to_cloud(test::kitti360_low().frames[0].points);
  LidarOdometry odom(OdometryConfig{});
  odom.register_frame(scan, 0.0);
  // The scene lifted 40 m (points still within range): nothing within reach of any start.
  Pose far = Pose::Identity();
  far.translation() = Vec3(0.0, 0.0, 40.0);
  const FrameResult fr = odom.register_frame(transformed(scan, far), 0.5);
  INFO(fr.registration.failure);
  CHECK_FALSE(fr.ok());
  CHECK_FALSE(fr.registration.converged);
  CHECK(fr.registration.failure.find("no overlap") != std::string::npos);
  CHECK(fr.registration.correspondences < 6);
}

TEST_CASE("register_scan reports an empty map and bad options", "[odometry]") {
  const Cloud scan = to_cloud(test::kitti360_low().frames[0].points);
  VoxelHashMap empty(1.0, 20, 80.0);
  const RegistrationResult r = register_scan(scan, empty, Pose::Identity(), RegistrationOptions{});
  CHECK_FALSE(r.converged);
  CHECK(r.iterations == 0);
  CHECK(r.failure == "the map is empty");
  RegistrationOptions bad;
  bad.max_distance = 0.0;
  CHECK_THROWS_AS(register_scan(scan, empty, Pose::Identity(), bad), ConfigError);
}
