// Trajectory and calibration files: round trips and errors naming file and line.
#include <catch2/catch.hpp>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "io/trajectory_io.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;

namespace {
std::vector<Pose> random_poses(int n, uint64_t seed) {
  Rng rng(seed);
  std::vector<Pose> v;
  for (int i = 0; i < n; ++i) {
    Vec6 xi;
    for (int k = 0; k < 6; ++k) xi[k] = rng.normal() * (k < 3 ? 0.5 : 10.0);
    v.push_back(exp_se3(xi));
  }
  return v;
}
}  // namespace

TEST_CASE("KITTI, KITTI-360 and TUM trajectories round trip exactly", "[io]") {
  const std::string dir = test::temp_dir("io_traj");
  const auto poses = random_poses(5, 3);
  io::write_kitti_poses(dir + "/k.txt", poses);
  io::write_indexed_poses(dir + "/p.txt", {3, 4, 8, 9, 20}, poses);
  std::vector<double> ts = {0.0, 0.1, 0.2, 0.3, 0.4};
  io::write_tum_poses(dir + "/t.tum", ts, poses);
  const auto k = io::read_kitti_poses(dir + "/k.txt");
  const auto p = io::read_indexed_poses(dir + "/p.txt");
  const auto t = io::read_tum_poses(dir + "/t.tum");
  REQUIRE(k.size() == 5);
  REQUIRE(p.size() == 5);
  REQUIRE(t.size() == 5);
  CHECK(p.count(8) == 1);
  CHECK(p.count(5) == 0);
  for (int i = 0; i < 5; ++i) {
    CHECK((k[size_t(i)].matrix() - poses[size_t(i)].matrix()).norm() == 0.0);  // %.17g is exact
    CHECK((t[size_t(i)].second.matrix() - poses[size_t(i)].matrix()).norm() < 1e-12);
    CHECK(t[size_t(i)].first == ts[size_t(i)]);
  }
  CHECK((p.at(20).matrix() - poses[4].matrix()).norm() == 0.0);
}

TEST_CASE("bad pose and calibration files name the file and line", "[io][bad-input]") {
  const std::string dir = test::temp_dir("io_traj_bad");
  write_text_file(dir + "/eleven.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1\n");
  CHECK_THROWS_WITH(io::read_kitti_poses(dir + "/eleven.txt"),
                    Catch::Contains("eleven.txt:2") && Catch::Contains("expected 12 numbers, found 11"));
  write_text_file(dir + "/poses.txt", "0 1 0 0 0 0 1 0 0 0 0 1 0\n1 1 0 0 0 0 1 0 0 0 0 1\n");
  CHECK_THROWS_WITH(io::read_indexed_poses(dir + "/poses.txt"), Catch::Contains("poses.txt:2"));
  write_text_file(dir + "/order.txt", "5 1 0 0 0 0 1 0 0 0 0 1 0\n5 1 0 0 0 0 1 0 0 0 0 1 0\n");
  CHECK_THROWS_WITH(io::read_indexed_poses(dir + "/order.txt"), Catch::Contains("order.txt:2"));
  write_text_file(dir + "/word.txt", "1 0 0 0 0 1 0 x 0 0 1 0\n");
  CHECK_THROWS_WITH(io::read_kitti_poses(dir + "/word.txt"), Catch::Contains("word.txt:1") && Catch::Contains("'x'"));
  write_text_file(dir + "/empty.txt", "\n");
  CHECK_THROWS_WITH(io::read_kitti_poses(dir + "/empty.txt"), Catch::Contains("no poses"));
  write_text_file(dir + "/skew.txt", "2 0 0 0 0 1 0 0 0 0 1 0\n");
  CHECK_THROWS_WITH(io::read_kitti_poses(dir + "/skew.txt"), Catch::Contains("not a rigid pose"));
  write_text_file(dir + "/calib.txt", "P0: 1 2 3\nTr: 1 0 0 0 0 1 0 0 0 0 1\n");
  const auto kv = io::read_key_values(dir + "/calib.txt");
  CHECK_THROWS_WITH(io::key_pose(kv, "Tr", dir + "/calib.txt"), Catch::Contains("calib.txt") && Catch::Contains("11 numbers"));
  CHECK_THROWS_WITH(io::key_pose(kv, "image_00", dir + "/calib.txt"), Catch::Contains("missing calibration entry 'image_00'"));
}
