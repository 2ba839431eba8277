// OdometryConfig: strict JSON (unknown keys rejected, bad values named), round trip, and the
// adaptive threshold and constant-velocity model against hand-computed values.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/config.hpp"
#include "odometry/adaptive_threshold.hpp"
#include "odometry/motion_model.hpp"
#include "odometry/odometry_config.hpp"

using namespace sgnlf;
using namespace sgnlf::odometry;

TEST_CASE("odometry config is read strictly", "[odometry][config]") {
  OdometryConfig c;
  c.coarse_threshold = 4.0;
  c.threads = 2;
  c.deskew = true;
  const Json j = c.to_json();
  ConfigReader r(j, "odo");
  const OdometryConfig back = OdometryConfig::from_json(r);
  CHECK(back.coarse_threshold == 4.0);
  CHECK(back.threads == 2);
  CHECK(back.deskew);
  CHECK_FALSE(OdometryConfig{}.deskew);  // off by default: the committed results ran without it
  CHECK(back.to_json() == j);

  Json unknown = j;
  unknown["voxel"] = 1.0;
  ConfigReader ru(unknown, "odo");
  CHECK_THROWS_WITH(OdometryConfig::from_json(ru), Catch::Contains("voxel"));
  Json bad = j;
  bad["min_range"] = 100.0;  // above max_range
  ConfigReader rb(bad, "odo");
  CHECK_THROWS_WITH(OdometryConfig::from_json(rb), Catch::Contains("min_range"));
  Json probe = j;
  probe["initial_search_iterations"] = -1;
  ConfigReader rp(probe, "odo");
  CHECK_THROWS_WITH(OdometryConfig::from_json(rp), Catch::Contains("initial_search_iterations"));
  Json passes = j;
  passes["deskew_passes"] = 0;
  ConfigReader rd(passes, "odo");
  CHECK_THROWS_WITH(OdometryConfig::from_json(rd), Catch::Contains("deskew_passes"));
  Json wrong = j;
  wrong["deskew"] = "yes";
  ConfigReader rw(wrong, "odo");
  CHECK_THROWS_WITH(OdometryConfig::from_json(rw), Catch::Contains("deskew"));
}

TEST_CASE("adaptive threshold follows KISS-ICP eq. 5-6", "[odometry]") {
  AdaptiveThreshold th(2.0, 0.1, 80.0);
  CHECK(th.sigma() == 2.0);
  Pose small = Pose::Identity();
  small.translation() = Vec3(0.05, 0, 0);
  th.update(small);  // below min_motion: not a sample
  CHECK(th.samples() == 0);
  Pose d = Pose::Identity();
  d.translation() = Vec3(0.3, 0.4, 0.0);
  d.linear() = exp_so3(Vec3(0, 0, 0.01));
  const double e = 0.5 + 2.0 * 80.0 * std::sin(0.005);
  CHECK(th.model_error(d) == Approx(e).epsilon(1e-12));
  th.update(d);
  th.update(small);
  CHECK(th.samples() == 1);
  CHECK(th.sigma() == Approx(e).epsilon(1e-12));
}

TEST_CASE("constant-velocity prediction scales with the time step", "[odometry]") {
  Pose a = Pose::Identity(), b = Pose::Identity();
  b.translation() = Vec3(2.0, 0, 0);
  CHECK(predict_constant_velocity({}, {}, 0.0).isApprox(Pose::Identity()));
  CHECK(predict_constant_velocity({a}, {0.0}, 0.5).isApprox(a));
  const Pose p = predict_constant_velocity({a, b}, {0.0, 0.5}, 1.25);  // 1.5 × the last step
  CHECK(p.translation().isApprox(Vec3(5.0, 0, 0)));
  const Pose q = predict_constant_velocity({a, b}, {0.0, 0.0}, 0.0);  // no clock: one step
  CHECK(q.translation().isApprox(Vec3(4.0, 0, 0)));
}
