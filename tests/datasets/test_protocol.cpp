// Protocol pieces: splits (§3), scene normalisation (§2), pose-noise initialisation (§3).
#include <catch2/catch.hpp>

#include <cmath>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "datasets/loader.hpp"
#include "datasets/protocol.hpp"

using namespace sgnlf;

TEST_CASE("protocol splits", "[protocol]") {
  const Split s = protocol_split(64, "standard");
  CHECK(s.test == std::vector<int>{13, 26, 39, 52});
  CHECK(s.train.size() == 60);
  const Split l = protocol_split(36, "low");
  CHECK(l.test == std::vector<int>{4, 12, 20});
  CHECK(l.train.size() == 33);
  CHECK(protocol_split(10, "low").test == std::vector<int>{4});
  CHECK_THROWS_AS(protocol_split(10, "high"), ConfigError);
}

TEST_CASE("scene normalisation: bbox midpoint, largest centred coordinate → 1", "[protocol]") {
  Dataset d;
  d.sensor = sensor_preset("kitti360");
  d.frames.resize(2);
  d.frames[0].points = {{1, 0, 0, 0}, {0, 3, 0, 0}, {90, 0, 0, 0}};  // 90 m: beyond range, ignored
  d.frames[1].points = {{-2, 0, 1, 0}};
  std::vector<Pose> T(2, Pose::Identity());
  T[1].translation() = Vec3(10, 0, 0);  // world: (1,0,0) (0,3,0) (8,0,1)
  const auto n = compute_normalization(d, T, {0, 1});
  CHECK(n.center.x() == Approx(4.0));
  CHECK(n.center.y() == Approx(1.5));
  CHECK(n.center.z() == Approx(0.5));
  CHECK(n.scale == Approx(1.0 / 4.0));
  const auto n0 = compute_normalization(d, T, {0});  // only frame 0's points
  CHECK(n0.center.x() == Approx(0.5));
  CHECK(n0.scale == Approx(1.0 / 1.5));
}

TEST_CASE("pose noise: T_gt · Exp(ξ) with ξ from Rng(seed), right-multiplied", "[protocol]") {
  std::vector<Pose> gt(3, Pose::Identity());
  gt[1].translation() = Vec3(5, 1, 0);
  gt[2].linear() = exp_so3(Vec3(0, 0, 0.7));
  const auto a = perturb_poses(gt, 1), b = perturb_poses(gt, 1), c = perturb_poses(gt, 2);
  Rng rng(1);
  for (size_t i = 0; i < gt.size(); ++i) {
    CHECK((a[i].matrix() - b[i].matrix()).norm() == 0.0);
    CHECK((a[i].matrix() - c[i].matrix()).norm() > 1e-3);
    Vec6 xi;
    for (int k = 0; k < 3; ++k) xi[k] = 0.151 * rng.normal();
    for (int k = 3; k < 6; ++k) xi[k] = 2.0 * rng.normal();
    CHECK(((gt[i] * exp_se3_decoupled(xi)).matrix() - a[i].matrix()).norm() < 1e-12);
  }
  // The draws have the protocol's spread.
  const auto many = perturb_poses(std::vector<Pose>(4000, Pose::Identity()), 7);
  double sr = 0, st = 0;
  for (const auto& T : many) {
    sr += log_so3(T.linear()).squaredNorm();
    st += T.translation().squaredNorm();
  }
  CHECK(std::sqrt(sr / (3 * 4000.0)) == Approx(0.151).epsilon(0.03));
  CHECK(std::sqrt(st / (3 * 4000.0)) == Approx(2.0).epsilon(0.03));
  const auto id = identity_poses(4);
  CHECK(id.size() == 4);
  CHECK(id[3].matrix() == Pose::Identity().matrix());
}

TEST_CASE("Load options: JSON round trip of the set keys, rejection of bad ones", "[protocol]") {
  LoadOptions o;
  CHECK(o.is_default());
  CHECK(o.to_json() == Json::object());
  o.sequence = "00";
  o.start = 40;
  o.frames = 10;
  o.test_frames = {3, 6};
  const Json j = o.to_json();
  CHECK(j.size() == 4);
  const LoadOptions back = LoadOptions::from_json(j, "test");
  CHECK(back == o);
  CHECK_FALSE(back.is_default());
  CHECK(back.test_frames == std::vector<int>{3, 6});
  CHECK_THROWS_WITH(LoadOptions::from_json(Json{{"test_frame", {1}}}, "where"),
                    Catch::Contains("test_frame"));
  CHECK_THROWS_WITH(LoadOptions::from_json(Json{{"test_frames", {1, 1}}}, "where"),
                    Catch::Contains("twice"));
  CHECK_THROWS_WITH(LoadOptions::from_json(Json{{"test_frames", {-2}}}, "where"),
                    Catch::Contains("-2"));
  CHECK_THROWS_WITH(LoadOptions::from_json(Json{{"test_frames", {1.5}}}, "where"),
                    Catch::Contains("1.5"));
  CHECK_THROWS_WITH(LoadOptions::from_json(Json{{"test_frames", 3}}, "where"),
                    Catch::Contains("test_frames"));
  CHECK_THROWS_AS(LoadOptions::from_json(Json{{"frames", 0}}, "where"), ConfigError);
}
