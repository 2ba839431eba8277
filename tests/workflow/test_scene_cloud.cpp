// scene_cloud: points moved by their frame's pose, in frame order, intensity kept; the voxel
// filter keeps the first point per voxel; pose counts checked.
#include <catch2/catch.hpp>

#include "geometry/se3.hpp"
#include "workflow/scene_cloud.hpp"

using namespace sgnlf;

TEST_CASE("scene_cloud moves each frame's points by its pose", "[workflow][cloud]") {
  Dataset d;
  d.frames.resize(2);
  d.frames[0].points = {{1.f, 0.f, 0.f, 0.25f}, {0.f, 2.f, 0.f, 0.5f}};
  d.frames[1].points = {{1.f, 0.f, 0.f, 0.75f}};
  Pose T0 = Pose::Identity();
  Pose T1 = Pose::Identity();
  T1.linear() = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()).toRotationMatrix();
  T1.translation() = Vec3(10, 0, 0);
  const auto c = workflow::scene_cloud(d, {T0, T1});
  REQUIRE(c.size() == 3);
  CHECK(c[0].x == 1.f);
  CHECK(c[1].y == 2.f);
  CHECK(c[2].x == Approx(10.0).margin(1e-6));
  CHECK(c[2].y == Approx(1.0).margin(1e-6));
  CHECK(c[2].intensity == 0.75f);

  // Frame 1's point lands on (10, 1, 0): a 0.5 m voxel filter keeps all three; two points in
  // one voxel keep the first.
  CHECK(workflow::scene_cloud(d, {T0, T1}, 0.5).size() == 3);
  d.frames[1].points = {{1.1f, 0.f, 0.f, 0.9f}};
  const auto v = workflow::scene_cloud(d, {T0, T0}, 0.5);
  REQUIRE(v.size() == 2);
  CHECK(v[0].intensity == 0.25f);

  CHECK_THROWS(workflow::scene_cloud(d, {T0}));
  CHECK_THROWS(workflow::scene_cloud(d, {T0, T0}, -1.0));
}
