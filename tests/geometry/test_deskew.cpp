// The per-point time model of a spinning LiDAR (geometry/sweep_timing.hpp) against hand-computed
// fractions, the presets' models, strict JSON, and deskewing (geometry/deskew.hpp) against
// hand-computed motions.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/config.hpp"
#include "geometry/deskew.hpp"
#include "geometry/sensor.hpp"

using namespace sgnlf;

namespace {
Vec3 at_azimuth_deg(double deg, double r = 10.0) {
  return Vec3(r * std::cos(deg * M_PI / 180.0), r * std::sin(deg * M_PI / 180.0), 0.5);
}
}  // namespace

TEST_CASE("sweep fraction follows the azimuth from the start, in the spin direction", "[geometry][deskew]") {
  SweepTiming cw;  // clockwise from 180°, reference mid-sweep (KITTI)
  CHECK(sweep_fraction(cw, at_azimuth_deg(179.999)) == Approx(0.0).margin(1e-4));
  CHECK(sweep_fraction(cw, at_azimuth_deg(90)) == Approx(0.25));
  CHECK(sweep_fraction(cw, at_azimuth_deg(0)) == Approx(0.5));
  CHECK(sweep_fraction(cw, at_azimuth_deg(-90)) == Approx(0.75));
  CHECK(sweep_fraction(cw, at_azimuth_deg(-179.999)) == Approx(1.0).margin(1e-4));
  CHECK(sweep_time_offset(cw, 0.1, at_azimuth_deg(0)) == Approx(0.0).margin(1e-15));
  CHECK(sweep_time_offset(cw, 0.1, at_azimuth_deg(90)) == Approx(-0.025));
  SweepTiming ccw{1, 0.0, 0.0};
  CHECK(sweep_fraction(ccw, at_azimuth_deg(90)) == Approx(0.25));
  CHECK(sweep_fraction(ccw, at_azimuth_deg(-90)) == Approx(0.75));
  for (double deg = -180; deg <= 180; deg += 7.3) {
    const double f = sweep_fraction(cw, at_azimuth_deg(deg));
    CHECK(f >= 0.0);
    CHECK(f < 1.0);
  }
}

TEST_CASE("the presets carry their sensor's time model; JSON keeps it only when it differs", "[geometry][deskew]") {
  const Sensor k = sensor_preset("kitti360"), n = sensor_preset("nuscenes");
  CHECK(k.sweep.reference == 0.5);
  CHECK(n.sweep.reference == 1.0);  // nuScenes stamps a sweep when its rotation is complete
  CHECK(n.sweep_duration_s() == Approx(0.05));
  CHECK(k.sweep_duration_s() == Approx(0.1));
  CHECK_FALSE(sensor_to_json(n).contains("sweep"));  // records written before it read the same
  CHECK(sensor_to_json(sensor_from_json(sensor_to_json(n), "n")).dump() == sensor_to_json(n).dump());
  CHECK(sensor_from_json(sensor_to_json(n), "n").sweep == n.sweep);
  Sensor custom = n;
  custom.sweep.start_azimuth_deg = 90.0;
  const Json j = sensor_to_json(custom);
  REQUIRE(j.contains("sweep"));
  CHECK(sensor_from_json(j, "custom").sweep == custom.sweep);
  Json bad = j;
  bad["sweep"]["direction"] = 0;
  CHECK_THROWS_WITH(sensor_from_json(bad, "bad.json"), Catch::Contains("direction"));
  Json unknown = j;
  unknown["sweep"]["phase"] = 1.0;
  CHECK_THROWS_WITH(sensor_from_json(unknown, "bad.json"), Catch::Contains("phase"));
}

TEST_CASE("deskewing moves each point by the motion between its time and the reference", "[geometry][deskew]") {
  const SweepTiming t{-1, 180.0, 1.0};  // nuScenes-like: the pose holds at the sweep's end
  const double dur = 0.05;
  Vec6 xi = Vec6::Zero();
  xi[3] = 10.0;  // 10 m/s forward, no rotation
  const std::vector<Vec3> pts{at_azimuth_deg(90), at_azimuth_deg(0), at_azimuth_deg(-90)};
  const auto out = deskew(pts, t, dur, xi);
  // f = 0.25, 0.5, 0.75 → τ = −37.5, −25, −12.5 ms → x shifted by −0.375, −0.25, −0.125 m.
  CHECK((out[0] - (pts[0] + Vec3(-0.375, 0, 0))).norm() < 1e-12);
  CHECK((out[1] - (pts[1] + Vec3(-0.25, 0, 0))).norm() < 1e-12);
  CHECK((out[2] - (pts[2] + Vec3(-0.125, 0, 0))).norm() < 1e-12);
  CHECK(deskew(pts, t, dur, Vec6::Zero()) == pts);
  // A pure yaw rate ω rotates each point about z by ω τ.
  Vec6 yaw = Vec6::Zero();
  yaw[2] = 0.4;
  const auto r = deskew(pts, t, dur, yaw);
  const Vec3 expect = Eigen::AngleAxisd(0.4 * -0.025, Vec3::UnitZ()) * pts[1];
  CHECK((r[1] - expect).norm() < 1e-12);
  // The velocity between two poses: 0.5 s apart, 2 m forward → 4 m/s.
  Pose b = Pose::Identity();
  b.translation() = Vec3(2, 0, 0);
  const Vec6 v = constant_velocity_twist(Pose::Identity(), b, 0.5);
  CHECK((v.tail<3>() - Vec3(4, 0, 0)).norm() < 1e-12);
  CHECK_THROWS(constant_velocity_twist(Pose::Identity(), b, 0.0));
}
