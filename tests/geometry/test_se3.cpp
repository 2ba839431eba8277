#include <catch2/catch.hpp>

#include "core/rng.hpp"
#include "geometry/se3.hpp"

using namespace sgnlf;

TEST_CASE("exp(log(T)) = T on random poses", "[se3]") {
  Rng rng(5);
  for (int i = 0; i < 100; ++i) {
    Vec6 xi;
    for (int k = 0; k < 6; ++k) xi[k] = rng.normal() * (k < 3 ? 0.8 : 3.0);
    const Pose T = exp_se3(xi);
    const Pose T2 = exp_se3(log_se3(T));
    CHECK((T.matrix() - T2.matrix()).norm() < 1e-9);
    if (xi.head<3>().norm() < M_PI - 1e-3) CHECK((log_se3(T) - xi).norm() < 1e-9);
    CHECK((exp_so3(xi.head<3>()) * exp_so3(xi.head<3>()).transpose() - Mat3::Identity()).norm() < 1e-12);
  }
}

TEST_CASE("rotation angle and decoupled exp", "[se3]") {
  const Vec3 w(0.0, 0.0, 0.3);
  CHECK(rotation_angle(exp_so3(w)) == Approx(0.3));
  Vec6 xi;
  xi << 0.1, -0.2, 0.05, 1.0, 2.0, -3.0;
  const Pose T = exp_se3_decoupled(xi);
  CHECK((T.translation() - Vec3(1, 2, -3)).norm() < 1e-15);
  const double v[12] = {1, 0, 0, 4, 0, 1, 0, 5, 0, 0, 1, 6};
  CHECK((pose_from_3x4(v).translation() - Vec3(4, 5, 6)).norm() == 0);
}
