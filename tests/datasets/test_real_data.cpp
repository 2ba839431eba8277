// The real data loads with the right counts and poses: the large excerpts in ../shared/data/real
// when present, else the in-repo sample datasets/real-sample (the same folders with fewer frames;
// the expectations below name both). The sample itself: test_real_sample.cpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include <algorithm>

#include "datasets/loader.hpp"
#include "io/scan_io.hpp"
#include "io/trajectory_io.hpp"
#include "support/real_data.hpp"

using namespace sgnlf;

namespace {
// The KITTI odometry frames each tree holds: the large slice 40-49, the sample 46-47.
struct KittiSlice {
  int first, last;
  size_t frames() const { return size_t(last - first + 1); }
};
KittiSlice kitti_slice(const test::RealData& r) { return r.full ? KittiSlice{40, 49} : KittiSlice{46, 47}; }
}  // namespace

TEST_CASE("nuScenes LIDAR_TOP frame: 34 688 points, rings 0-31", "[real]") {
  // The same file in both trees (byte for byte, test_real_sample.cpp).
  const test::RealData r = test::real_data("nuscenes-lidar-top-single");
  if (!r) return;
  const std::string dir = r.path;
  const std::string file = dir + "/n015-2018-07-24-11-22-45+0800__LIDAR_TOP__1532402927647951.pcd.bin";
  std::vector<uint8_t> rings;
  io::ScanReadStats st;
  const auto pts = io::read_nuscenes_bin(file, &st, &rings);
  CHECK(pts.size() == 34688);
  CHECK(st.non_finite == 0);
  CHECK(*std::min_element(rings.begin(), rings.end()) == 0);
  CHECK(*std::max_element(rings.begin(), rings.end()) == 31);
  for (const auto& p : pts) REQUIRE((p.intensity >= 0.f && p.intensity <= 1.f));
  // The folder and the file both load as a one-frame dataset with the nuScenes sensor.
  for (const auto& path : {dir, file}) {
    const Dataset d = load_dataset(path);
    REQUIRE(d.frames.size() == 1);
    CHECK(d.sensor.name == "nuscenes");
    // The frame keeps the in-range returns only: 34 688 records less 8 474 within 1.8 m (the
    // vehicle itself) and 142 at >= 80 m, the counts the range image drops.
    CHECK(d.frames[0].points.size() == 26072);
    for (const auto& p : d.frames[0].points)
      REQUIRE(d.sensor.in_range(std::sqrt(double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z)));
    size_t ret = 0;
    for (float r : d.frames[0].image.range) ret += r > 0.f;
    CHECK(ret > 20000);  // measured 24 650 of 34 560 pixels
    CHECK(ret < 34560);
  }
}

TEST_CASE("KITTI odometry slice: 10 frames (sample: 2), LiDAR poses inv(Tr)·P·Tr", "[real]") {
  const test::RealData r = test::real_data("kitti-odometry-00-slice");
  if (!r) return;
  const std::string root = r.path;
  const KittiSlice k = kitti_slice(r);
  const Dataset d = load_dataset(root);
  CHECK(d.source == "kitti-odometry");
  REQUIRE(d.frames.size() == k.frames());
  CHECK(d.frames.front().id == k.first);
  CHECK(d.frames.back().id == k.last);
  CHECK(d.frames[1].timestamp_s == Approx(0.1037).margin(2e-3));
  for (const auto& f : d.frames) {
    CHECK(f.points.size() > 100000);
    CHECK(f.points.size() < 130000);
  }
  const auto kv = io::read_key_values(root + "/sequences/00/calib.txt");
  const Pose Tr = io::key_pose(kv, "Tr", "calib.txt");
  const auto P = io::read_kitti_poses(root + "/poses/00.txt");
  REQUIRE(P.size() == size_t(k.last) + 1);  // line i is frame i
  const size_t last = d.frames.size() - 1;
  const Pose T_last = Tr.inverse() * P[size_t(k.last)] * Tr;
  CHECK((T_last.matrix() - d.frames[last].T_world_lidar.matrix()).norm() < 1e-9);
  // Step length per frame. The ground truth of rows 40-49 steps 1.00-1.06 m; 0.86 m is the
  // step of rows 0-14 (an alignment of scans 40 and 41 also finds ~1.0 m, see the README).
  double mean = 0;
  for (size_t i = 1; i < d.frames.size(); ++i) {
    const double step =
        (d.frames[i].T_world_lidar.translation() - d.frames[i - 1].T_world_lidar.translation()).norm();
    CHECK(step > 0.95);
    CHECK(step < 1.10);
    mean += step / double(last);
  }
  if (r.full) CHECK(mean == Approx(1.03).margin(0.02));
  CHECK(d.split.test.empty());  // 10 frames: no standard-frequency test frame before 13
}

TEST_CASE("KITTI odometry slice: test frames chosen by position replace the protocol split",
          "[real]") {
  const test::RealData r = test::real_data("kitti-odometry-00-slice");
  if (!r) return;
  const std::string root = r.path;
  LoadOptions o;
  o.test_frames = r.full ? std::vector<int>{6, 3} : std::vector<int>{1};
  const Dataset d = load_dataset(root, o);
  CHECK(d.split.test == (r.full ? std::vector<int>{3, 6} : std::vector<int>{1}));
  CHECK(d.split.train == (r.full ? std::vector<int>{0, 1, 2, 4, 5, 7, 8, 9} : std::vector<int>{0}));
  // A window: frames 42.. of the slice (sample: 46..), positions relative to it.
  const int n = r.full ? 5 : 2;
  o.start = r.full ? 42 : 46;
  o.frames = n;
  o.test_frames = {n / 2};
  const Dataset w = load_dataset(root, o);
  REQUIRE(w.frames.size() == size_t(n));
  CHECK(w.frames[size_t(w.split.test.at(0))].id == (r.full ? 44 : 47));
  // Positions past the window, or every frame held out: errors naming the value.
  o.test_frames = {n};
  CHECK_THROWS_WITH(load_dataset(root, o), Catch::Contains("position " + std::to_string(n)) &&
                                               Catch::Contains("0.." + std::to_string(n - 1)));
  o.test_frames.clear();
  for (int i = 0; i < n; ++i) o.test_frames.push_back(i);
  CHECK_THROWS_WITH(load_dataset(root, o), Catch::Contains("no training frame"));
}

TEST_CASE("nuScenes scene-0916: keyframes in time order, poses as the independent reference",
          "[real]") {
  const test::RealData r = test::real_data("nuscenes-mini-scene-0916");
  if (!r) return;
  LoadOptions o;
  o.sequence = "scene-0916";
  const Dataset d = load_dataset(r.path, o);  // low frequency: the 2 Hz keyframes, at most 36
  CHECK(d.source == "nuscenes");
  CHECK(d.frequency == "low");
  CHECK(d.sensor.name == "nuscenes");
  // The large scene holds 41 keyframes (the protocol window takes 36), the sample its first 2.
  REQUIRE(d.frames.size() == (r.full ? 36u : 2u));
  CHECK(d.split.test == (r.full ? std::vector<int>{4, 12, 20} : std::vector<int>{}));
  // times.txt and reference_poses_lidar_world.txt were computed from the same tables without
  // sgnlf (one line a keyframe, time order): T_world_lidar = T_world_ego · T_ego_lidar.
  std::ifstream tf(r.path + "/times.txt");
  std::vector<double> times;
  for (double t; tf >> t;) times.push_back(t);
  const auto ref = io::read_kitti_poses(r.path + "/reference_poses_lidar_world.txt");
  REQUIRE(times.size() == (r.full ? 41u : 2u));
  REQUIRE(ref.size() == times.size());
  for (size_t i = 0; i < d.frames.size(); ++i) {
    INFO("keyframe " << i);
    CHECK(d.frames[i].id == int(i));
    CHECK(d.frames[i].timestamp_s == Approx(times[i]).margin(1e-6));
    CHECK((d.frames[i].T_world_lidar.matrix() - ref[i].matrix()).norm() < 1e-6);
    // ~34 700 records a scan; the vehicle's own returns (< 1.8 m) and >= 80 m are not kept.
    CHECK(d.frames[i].points.size() > 20000);
    CHECK(d.frames[i].points.size() < 34700);
  }
  // 2 Hz: the first step is 0.50 s and 1.6-3.1 m (README of the large data).
  CHECK(d.frames[1].timestamp_s == Approx(0.5).margin(0.01));
  const double step =
      (d.frames[1].T_world_lidar.translation() - d.frames[0].T_world_lidar.translation()).norm();
  CHECK(step > 1.6);
  CHECK(step < 3.1);
}
