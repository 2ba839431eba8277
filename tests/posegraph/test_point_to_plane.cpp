// Point-to-plane direction term and the normals it uses: normals of planes, lines and sparse
// neighbourhoods; the analytic gradient of both frames against central differences; and the
// reason the term exists — on one plane sampled in rings from two sensor positions metres apart
// (2 Hz keyframes), point-to-point Chamfer pulls the frames together at the TRUE pose while the
// plane residual is zero there.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "core/rng.hpp"
#include "posegraph/geometric_optimizer.hpp"
#include "posegraph/point_to_plane.hpp"
#include "posegraph/pose_adam.hpp"
#include "gradient_fixture.hpp"
#include "smooth_scene.hpp"

using namespace sgnlf;
using namespace sgnlf::posegraph;
using namespace sgnlf::test;

namespace {

// Rings of a sensor 1.8 m above flat ground: the pattern a spinning LiDAR leaves there. Points
// in the sensor's frame (origin at the sensor).
std::vector<geometry::Point3f> ground_rings(int rings, int per_ring) {
  std::vector<geometry::Point3f> pts;
  for (int r = 0; r < rings; ++r) {
    const double radius = 4.0 + 0.5 * r + 0.01 * r * r;  // rings spread out with distance
    for (int k = 0; k < per_ring; ++k) {
      const double a = 2.0 * M_PI * (k + 0.37 * r) / per_ring;
      pts.emplace_back(float(radius * std::cos(a)), float(radius * std::sin(a)), -1.8f);
    }
  }
  return pts;
}

}  // namespace

TEST_CASE("normals: a tilted plane's normal towards the sensor, none on a line or when sparse",
          "[posegraph]") {
  Rng rng(3);
  std::vector<geometry::Point3f> plane, line;
  for (int k = 0; k < 4000; ++k) {
    const double x = rng.uniform_double() * 10 - 5, y = rng.uniform_double() * 10 - 5;
    plane.emplace_back(float(x), float(y), float(0.3 * x - 2.0));
    line.emplace_back(float(x), 1.0f, 2.0f);
  }
  NormalOptions o;
  const auto n = estimate_normals({plane[0], plane[1], plane[2]}, plane, o);
  const Eigen::Vector3f expect = Eigen::Vector3f(-0.3f, 0.f, 1.f).normalized();
  for (const auto& v : n) {
    CHECK(std::abs(v.norm() - 1.f) < 1e-5f);
    CHECK(std::abs(v.dot(expect)) > 0.9999f);
  }
  CHECK(n[0].dot(plane[0]) <= 0.f);  // faces the sensor at the origin
  for (const auto& v : estimate_normals({line[0], line[1]}, line, o)) CHECK(v.squaredNorm() == 0.f);
  const std::vector<geometry::Point3f> sparse = {plane[0], plane[1], plane[2]};
  for (const auto& v : estimate_normals(sparse, sparse, o)) CHECK(v.squaredNorm() == 0.f);
  o.min_neighbours = 2;
  CHECK_THROWS_WITH(estimate_normals(sparse, plane, o), Catch::Contains("min_neighbours"));
}

TEST_CASE("point-to-plane term: gradient of both frames matches central differences",
          "[posegraph][gradient]") {
  const auto src = test::cloud_seen_from(test::smooth_world_points(600, 3), kBase0);
  auto dst = test::cloud_seen_from(test::smooth_world_points(4000, 4), kBase1);
  Rng rng(9);  // any fixed normals: the gradient holds for every constant normal field
  for (size_t k = 0; k < dst.size(); ++k) {
    Eigen::Vector3f v(float(rng.uniform_double() - 0.5), float(rng.uniform_double() - 0.5),
                      float(rng.uniform_double() - 0.5));
    dst.normals.push_back(k % 7 == 0 ? Eigen::Vector3f::Zero() : Eigen::Vector3f(v.normalized()));
  }
  const Pose T0 = corrected_pose(kBase0, kXi0), T1 = corrected_pose(kBase1, kXi1);
  const auto m = match_direction(src, dst, T1.inverse() * T0);
  const auto w = robust_weights(m, {0.6, 0.15});
  auto f = [&](const Vec6& x0, const Vec6& x1) {
    const Pose A = corrected_pose(kBase0, x0), B = corrected_pose(kBase1, x1);
    return weighted_plane_direction(src, dst, A, B, match_direction(src, dst, B.inverse() * A), w)
        .loss;
  };
  const auto t = weighted_plane_direction(src, dst, T0, T1, m, w);
  const Eigen::VectorXd analytic = stack(decoupled_gradient(kBase0, kXi0, t.grad_src),
                                         decoupled_gradient(kBase1, kXi1, t.grad_dst));
  const Eigen::VectorXd numeric = central_differences(f, 1e-6);
  INFO("analytic " << analytic.transpose() << "\nnumeric  " << numeric.transpose());
  CHECK(sym_rel_error(analytic, numeric) < 1e-5);
  CHECK(numeric.norm() > 0.01);
  CHECK(sym_rel_error(-analytic, numeric) > 1.9);
  // Without normals the term refuses, naming the cause.
  const auto bare = test::cloud_seen_from(test::smooth_world_points(100, 4), kBase1);
  CHECK_THROWS_WITH(point_to_plane_direction(src, bare, T0, T1, {0.0, 0.15}),
                    Catch::Contains("normals"));
}

TEST_CASE("on ground rings seen 3 m apart, point-to-point is biased at the true pose and "
          "point-to-plane is not", "[posegraph]") {
  // The same flat ground, scanned in rings from two sensor positions 3 m apart along x.
  std::vector<std::vector<PointXYZI>> scans(2);
  for (int f = 0; f < 2; ++f)
    for (const auto& p : ground_rings(24, 900)) scans[f].push_back({p.x(), p.y(), p.z(), 0.f});
  const Pose T0 = Pose::Identity();
  Pose T1 = Pose::Identity();
  T1.translation() = Vec3(3.0, 0.0, 0.0);
  GeometricConfig c;
  c.points_per_frame = 0;  // all points
  c.residual = "point_to_plane";
  const auto clouds = c.clouds(scans);
  REQUIRE(clouds[1].normals.size() == clouds[1].size());
  size_t planar = 0;
  for (const auto& n : clouds[1].normals) planar += std::abs(n.z()) > 0.999f;
  CHECK(planar > clouds[1].size() * 9 / 10);
  const auto plane = point_to_plane_direction(clouds[0], clouds[1], T0, T1, {0.0, 0.15});
  const auto point = robust_chamfer_direction(clouds[0], clouds[1], T0, T1, {0.0, 0.15});
  // Along the ground (x, y translation) the ring pattern pulls point-to-point; the plane term
  // has no residual at the true pose, so no pull.
  const double pull_point = point.grad_src.segment<2>(3).norm();
  const double pull_plane = plane.grad_src.segment<2>(3).norm();
  INFO("point-to-point pull " << pull_point << ", point-to-plane " << pull_plane);
  CHECK(pull_point > 1e-2);
  CHECK(pull_plane < 1e-4 * pull_point);
  CHECK(plane.loss < 1e-8);
}
