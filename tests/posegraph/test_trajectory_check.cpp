// The convergence check of a trajectory (posegraph/trajectory_check.hpp): frames seen from a
// straight drive over smooth surfaces are all converged at the true poses; one frame moved 3 m
// breaks its edges (suspect, not converged); every frame scrambled breaks the median; bad config
// values and pose counts are refused.
#include <catch2/catch.hpp>

#include "core/config.hpp"
#include "core/error.hpp"
#include "posegraph/trajectory_check.hpp"
#include "smooth_scene.hpp"

using namespace sgnlf;
using namespace sgnlf::posegraph;

namespace {

struct Drive {
  std::vector<Pose> T;
  std::vector<FrameCloud> clouds;
};

// 8 frames 1 m apart along x; each sees its own 3000-point sample of the same surfaces.
Drive drive() {
  Drive d;
  for (int k = 0; k < 8; ++k) {
    Pose T = Pose::Identity();
    T.translation() = Vec3(double(k), 0.2 * std::sin(k), 0.0);
    d.T.push_back(T);
    d.clouds.push_back(test::cloud_seen_from(test::smooth_world_points(3000, 10 + uint64_t(k)), T));
  }
  return d;
}

}  // namespace

TEST_CASE("trajectory check: true poses converge, a moved frame does not", "[trajectory_check]") {
  const Drive d = drive();
  const auto edges = sequential_edges(8, {1});
  const TrajectoryCheck ok = check_trajectory(d.clouds, d.T, edges);
  CHECK(ok.converged);
  CHECK(ok.reason.empty());
  CHECK(ok.suspect_edges() == 0);
  CHECK(ok.median_overlap > 0.5);
  REQUIRE(ok.edges.size() == 7);
  CHECK(ok.to_json().at("converged").get<bool>());

  std::vector<Pose> moved = d.T;
  moved[4].translation() += Vec3(0.0, 3.0, 0.0);
  const TrajectoryCheck bad = check_trajectory(d.clouds, moved, edges);
  CHECK_FALSE(bad.converged);
  CHECK(bad.suspect_edges() == 2);  // (3, 4) and (4, 5)
  for (const auto& e : bad.edges) CHECK(e.suspect == (e.i == 3 || e.i == 4));
  CHECK(bad.reason.find("2 of 7 edges") != std::string::npos);
  CHECK(bad.to_json().at("suspect_edges").size() == 2);
}

TEST_CASE("trajectory check: scrambled poses fail on the median, jumps are reported",
          "[trajectory_check]") {
  const Drive d = drive();
  std::vector<Pose> scrambled = d.T;
  for (size_t k = 0; k < scrambled.size(); ++k) {
    scrambled[k].translation() += Vec3(k % 2 ? 4.0 : -4.0, k % 3 ? 3.0 : -3.0, 0.0);
    scrambled[k].linear() = exp_so3(Vec3(0.0, 0.0, 0.5 * double(k % 3) - 0.5)) * scrambled[k].linear();
  }
  const TrajectoryCheck bad = check_trajectory(d.clouds, scrambled, sequential_edges(8, {1}));
  CHECK_FALSE(bad.converged);
  CHECK(bad.median_overlap < 0.2);
  CHECK(bad.reason.find("do not register") != std::string::npos);

  std::vector<Pose> jump = d.T;
  for (size_t k = 5; k < jump.size(); ++k) jump[k].translation() += Vec3(20.0, 0.0, 0.0);
  const TrajectoryCheck j = check_trajectory(d.clouds, jump, sequential_edges(8, {1}));
  CHECK(j.jumps == std::vector<int>{4});
  CHECK_FALSE(j.converged);
}

TEST_CASE("trajectory check: bad input is refused with the field named", "[trajectory_check]") {
  const Drive d = drive();
  TrajectoryCheckConfig c;
  c.edge_ratio = 1.5;
  CHECK_THROWS_WITH(check_trajectory(d.clouds, d.T, sequential_edges(8, {1}), c),
                    Catch::Contains("edge_ratio"));
  std::vector<Pose> short_T(d.T.begin(), d.T.begin() + 3);
  CHECK_THROWS_AS(check_trajectory(d.clouds, short_T, sequential_edges(8, {1})), Error);
}
