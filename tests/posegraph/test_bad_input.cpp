// Bad input: config fields named in errors, mismatched poses and clouds, non-finite poses,
// invalid edges; and the deterministic subsample.
#include <catch2/catch.hpp>

#include <algorithm>
#include <limits>

#include "core/error.hpp"
#include "posegraph/geometric_optimizer.hpp"
#include "smooth_scene.hpp"

using namespace sgnlf;
using namespace sgnlf::posegraph;

namespace {

std::vector<FrameCloud> three_clouds() {
  std::vector<FrameCloud> c;
  for (int k = 0; k < 3; ++k)
    c.push_back(test::cloud_seen_from(test::smooth_world_points(300, 20 + k), Pose::Identity()));
  return c;
}

template <class Mutate>
void check_config_error(Mutate mutate, const std::string& field) {
  GeometricConfig c;
  mutate(c);
  try {
    c.validate();
    FAIL("validate() accepted a bad " << field);
  } catch (const ConfigError& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find("GeometricConfig." + field) != std::string::npos);
  }
}

}  // namespace

TEST_CASE("GeometricConfig::validate names the bad field", "[posegraph][config]") {
  CHECK_NOTHROW(GeometricConfig{}.validate());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  check_config_error([](auto& c) { c.edge_offsets = {}; }, "edge_offsets");
  check_config_error([](auto& c) { c.edge_offsets = {1, 0}; }, "edge_offsets");
  check_config_error([](auto& c) { c.steps = -1; }, "steps");
  check_config_error([](auto& c) { c.lr_rotation = 0; }, "lr_rotation");
  check_config_error([&](auto& c) { c.lr_translation = nan; }, "lr_translation");
  check_config_error([](auto& c) { c.tau_scale = -0.3; }, "tau_scale");
  check_config_error([](auto& c) { c.min_distance = 0; }, "min_distance");
  check_config_error([](auto& c) { c.threads = 0; }, "threads");
  GeometricConfig bad;
  bad.lr_rotation = -1;
  CHECK_THROWS_AS(GeometricOptimizer(three_clouds(), bad), ConfigError);
}

TEST_CASE("run() rejects mismatched poses, non-finite poses and bad progress",
          "[posegraph][config]") {
  const GeometricOptimizer opt(three_clouds(), GeometricConfig{});
  std::vector<Pose> two(2, Pose::Identity());
  CHECK_THROWS_WITH(opt.run(two, 0.5), Catch::Contains("2 poses for 3 frames"));
  std::vector<Pose> T(3, Pose::Identity());
  T[1].translation().x() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(opt.run(T, 0.5), Catch::Contains("pose of frame 1 is not finite"));
  T[1] = Pose::Identity();
  CHECK_THROWS_WITH(opt.run(T, 1.5), Catch::Contains("progress"));
  const auto r = opt.run(T, 0.5);  // identical frames at identical poses: already optimal
  CHECK(r.steps == 10);
  CHECK(r.loss_after <= r.loss_before + 1e-12);
}

TEST_CASE("edges: GeoNLF generator and validation", "[posegraph][edges]") {
  const auto e = sequential_edges(4);
  REQUIRE(e.size() == 5);  // (0,1) (1,2) (2,3) (0,2) (1,3)
  CHECK((e[0].i == 0 && e[0].j == 1 && e[3].i == 0 && e[3].j == 2 && e[4].j == 3));
  CHECK(e[2].weight == 1.0);
  CHECK_THROWS_AS(sequential_edges(4, {0}), ConfigError);
  CHECK_THROWS_WITH(validate_edges({Edge{0, 3, 1}}, 3), Catch::Contains("edge 0 (0, 3)"));
  CHECK_THROWS_WITH(validate_edges({Edge{1, 1, 1}}, 3), Catch::Contains("itself"));
  CHECK_THROWS_WITH(validate_edges({Edge{0, 1, -1}}, 3), Catch::Contains("weight"));
  CHECK_THROWS_AS(validate_edges({}, 3), Error);
  CHECK_THROWS_AS(GeometricOptimizer(three_clouds(), GeometricConfig{}, {Edge{0, 5, 1}}), Error);
  CHECK_THROWS_AS(FrameCloud({}), Error);
}

TEST_CASE("subsample: deterministic, without replacement, sorted", "[posegraph][subsample]") {
  const auto a = subsample_indices(1000, 100, 7, 3);
  CHECK(a == subsample_indices(1000, 100, 7, 3));
  CHECK(a != subsample_indices(1000, 100, 7, 4));
  CHECK(a != subsample_indices(1000, 100, 8, 3));
  REQUIRE(a.size() == 100);
  CHECK(std::is_sorted(a.begin(), a.end()));
  CHECK(std::adjacent_find(a.begin(), a.end()) == a.end());
  CHECK(a.back() < 1000);
  CHECK(subsample_indices(50, 100, 7, 3).size() == 50);
  CHECK(subsample_indices(50, 0, 7, 3).size() == 50);
}
