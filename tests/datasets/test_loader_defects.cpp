// Regression tests for loader defects found by reading the code: a stride of
// 0 or below, over-long numeric scan names, non-rigid KITTI-360 calibrations, zero quaternions
// and JSON type errors in the nuScenes tables, sensors with gigabyte range images, and test
// folders that two checkouts shared.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>

#include "core/config.hpp"
#include "core/error.hpp"
#include "datasets/loader.hpp"
#include "datasets/loader_internal.hpp"
#include "geometry/sensor.hpp"
#include "io/scan_io.hpp"
#include "io/trajectory_io.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;
namespace fs = std::filesystem;

namespace {

const char* kDrive = "2013_05_28_drive_0000_sync";

std::string pose12(const Pose& T) {
  double v[12];
  pose_to_3x4(T, v);
  std::string s;
  char b[40];
  for (int k = 0; k < 12; ++k) {
    std::snprintf(b, sizeof(b), "%.17g", v[k]);
    s += (k ? " " : "") + std::string(b);
  }
  return s;
}

std::string scan_name(int id) {
  char n[32];
  std::snprintf(n, sizeof(n), "%010d.bin", id);
  return n;
}

// A KITTI-360 tree with frames 0..4 (identity calibrations); `synthetic` adds the files that
// make it the synthetic layout (sgnlf_dataset.json, sensor.json).
std::string kitti360_tree(const std::string& name, bool synthetic, int meta_stride = 1) {
  const std::string root = test::temp_dir(name);
  fs::create_directories(root + "/calibration");
  fs::create_directories(root + "/data_poses/" + kDrive);
  write_text_file(root + "/calibration/calib_cam_to_pose.txt", "image_00: " + pose12(Pose::Identity()) + "\n");
  write_text_file(root + "/calibration/calib_cam_to_velo.txt", pose12(Pose::Identity()) + "\n");
  std::string poses;
  for (int id = 0; id < 5; ++id) {
    Pose T = Pose::Identity();
    T.translation() = Vec3(double(id), 0, 0);
    poses += std::to_string(id) + " " + pose12(T) + "\n";
    io::write_kitti_bin(root + "/data_3d_raw/" + kDrive + "/velodyne_points/data/" + scan_name(id),
                        {{5.f + float(id), 1.f, -1.f, 0.3f}, {-7.f, 2.f, 0.5f, 0.6f}});
  }
  write_text_file(root + "/data_poses/" + kDrive + "/poses.txt", poses);
  if (synthetic) {
    write_json_file(root + "/sgnlf_dataset.json",
                    Json{{"name", "fake"}, {"sequence", kDrive}, {"frequency", "standard"},
                         {"first_frame", 0}, {"stride", meta_stride}, {"frames", 4}});
    write_json_file(root + "/sensor.json", sensor_to_json(sensor_preset("kitti360")));
  }
  return root;
}

Json quat_pose(const std::string& token, Json rotation) {
  return Json{{"token", token}, {"rotation", rotation}, {"translation", {1.0, 2.0, 0.5}}};
}

// The smallest nuScenes tree: one scene, one LIDAR_TOP keyframe.
struct NuScenesTree {
  std::string root, tdir;
  Json scene, sample, sensor, cal, ego, sd;
  explicit NuScenesTree(const std::string& name) : root(test::temp_dir(name)), tdir(root + "/v1.0-mini") {
    fs::create_directories(tdir);
    scene = Json::array({{{"token", "sc1"}, {"name", "scene-0001"}}});
    sample = Json::array({{{"token", "s1"}, {"scene_token", "sc1"}}});
    sensor = Json::array({{{"token", "lid"}, {"channel", "LIDAR_TOP"}}});
    cal = Json::array({quat_pose("c1", {1.0, 0.0, 0.0, 0.0})});
    cal[0]["sensor_token"] = "lid";
    ego = Json::array({quat_pose("e1", {0.0, 0.0, 0.0, 1.0})});
    sd = Json::array({{{"token", "d1"}, {"sample_token", "s1"}, {"ego_pose_token", "e1"},
                       {"calibrated_sensor_token", "c1"}, {"timestamp", 1000000}, {"is_key_frame", true},
                       {"filename", "samples/LIDAR_TOP/a.pcd.bin"}}});
    const std::vector<float> v = {3, 1, -1, 102, 5, -6, 2, 0.5f, 255, 20};
    fs::create_directories(root + "/samples/LIDAR_TOP");
    io::write_file_bytes(root + "/samples/LIDAR_TOP/a.pcd.bin", v.data(), v.size() * 4);
  }
  void write() const {
    write_json_file(tdir + "/scene.json", scene);
    write_json_file(tdir + "/sample.json", sample);
    write_json_file(tdir + "/sensor.json", sensor);
    write_json_file(tdir + "/calibrated_sensor.json", cal);
    write_json_file(tdir + "/ego_pose.json", ego);
    write_json_file(tdir + "/sample_data.json", sd);
  }
};

}  // namespace

TEST_CASE("a stride of 0 or below is refused, never repeats a frame or hangs", "[layout][bad-input]") {
  // The window selection itself: before the fix stride 0 returned one id `count` times (or
  // looped forever when the id was missing), a negative one walked backwards.
  const std::vector<int> avail = {0, 1, 2, 3, 4};
  CHECK(detail::select_window(avail, 0, 2, 3, "w") == std::vector<int>{0, 2, 4});
  CHECK(detail::select_window({0, 0, 1}, 0, 1, 3, "w") == std::vector<int>{0, 1});  // "0.bin" and "00.bin"
  CHECK_THROWS_WITH(detail::select_window(avail, 0, 0, 3, "win"), Catch::Contains("win") && Catch::Contains("stride 0"));
  CHECK_THROWS_WITH(detail::select_window(avail, 3, -1, 3, "win"), Catch::Contains("stride -1"));
  CHECK_THROWS_AS(detail::select_window(avail, 0, 1, 0, "win"), ConfigError);
  // A far start costs one pass over the available ids, not a walk over 2^31 grid ids.
  CHECK(detail::select_window({5, 2147483647}, 0, 1, 2, "w") == std::vector<int>{5, 2147483647});

  // The dataset description of the synthetic layout: stride 0 and -2 name the file and key.
  for (int bad : {0, -2}) {
    const std::string root = kitti360_tree("stride_" + std::to_string(bad + 10), true, bad);
    CHECK_THROWS_WITH(load_dataset(root), Catch::Contains("sgnlf_dataset.json") && Catch::Contains("'stride'"));
  }
  const std::string good = kitti360_tree("stride_ok", true, 2);
  const Dataset d = load_dataset(good);
  REQUIRE(d.frames.size() == 3);  // 0, 2, 4
  CHECK(d.frames[1].id == 2);
  // Wrong JSON types in the description name the file, not nlohmann's type_error.
  Json meta = load_json_file(good + "/sgnlf_dataset.json");
  meta["frames"] = "four";
  write_json_file(good + "/sgnlf_dataset.json", meta);
  CHECK_THROWS_WITH(load_dataset(good), Catch::Contains("sgnlf_dataset.json") && Catch::Contains("'frames'"));
  // Options: stride and frames below 1 are ConfigErrors before anything is read.
  LoadOptions o;
  o.stride = 0;
  CHECK_THROWS_AS(load_dataset(good, o), ConfigError);
  o.stride = -3;
  CHECK_THROWS_AS(load_dataset(good, o), ConfigError);
}

TEST_CASE("an over-long numeric scan file name names the file", "[layout][bad-input]") {
  const std::string root = kitti360_tree("long_name", false);
  const std::string dir = root + "/data_3d_raw/" + kDrive + "/velodyne_points/data/";
  io::write_kitti_bin(dir + "99999999999999999999.bin", {{1.f, 1.f, 1.f, 0.5f}});
  LoadOptions o;
  o.start = 0;
  CHECK_THROWS_WITH(load_dataset(root, o),
                    Catch::Contains("99999999999999999999.bin") && Catch::Contains("out of range"));
  fs::remove(dir + "99999999999999999999.bin");
  // The largest int still loads its neighbours (leading zeros are fine).
  io::write_kitti_bin(dir + "00002147483647.bin", {{1.f, 1.f, 1.f, 0.5f}});
  CHECK(load_dataset(root, o).frames.size() == 5);
  io::write_kitti_bin(dir + "2147483648.bin", {{1.f, 1.f, 1.f, 0.5f}});
  CHECK_THROWS_WITH(load_dataset(root, o), Catch::Contains("2147483648.bin"));
}

TEST_CASE("KITTI-360 calibrations must be rigid", "[layout][bad-input]") {
  const std::string root = kitti360_tree("calib_rigid", false);
  LoadOptions o;
  o.start = 0;
  REQUIRE(load_dataset(root, o).frames.size() == 5);
  // A scale (a projection-like matrix under the wrong key), a shear and a reflection.
  const std::string scaled = "image_00: 2 0 0 0 0 2 0 0 0 0 2 0\n";
  write_text_file(root + "/calibration/calib_cam_to_pose.txt", scaled);
  CHECK_THROWS_WITH(load_dataset(root, o), Catch::Contains("calib_cam_to_pose.txt") &&
                                               Catch::Contains("image_00") && Catch::Contains("rigid"));
  write_text_file(root + "/calibration/calib_cam_to_pose.txt", "image_00: " + pose12(Pose::Identity()) + "\n");
  write_text_file(root + "/calibration/calib_cam_to_velo.txt", "1 0.1 0 0 0 1 0 0 0 0 1 0\n");
  CHECK_THROWS_WITH(load_dataset(root, o), Catch::Contains("calib_cam_to_velo.txt") && Catch::Contains("rigid"));
  write_text_file(root + "/calibration/calib_cam_to_velo.txt", "-1 0 0 0 0 1 0 0 0 0 1 0\n");
  CHECK_THROWS_WITH(load_dataset(root, o), Catch::Contains("calib_cam_to_velo.txt") && Catch::Contains("reflection"));
  // The same check guards KITTI odometry's Tr (io::key_pose).
  const auto kv = io::read_key_values(root + "/calibration/calib_cam_to_velo.txt");
  CHECK_THROWS_AS(io::key_pose(kv, "", "calib.txt"), IoError);
}

TEST_CASE("nuScenes: a zero or non-unit quaternion is refused, not made the identity", "[layout][bad-input]") {
  NuScenesTree t("nus_quat");
  t.write();
  REQUIRE(load_dataset(t.root).frames.size() == 1);
  t.ego[0]["rotation"] = {0.0, 0.0, 0.0, 0.0};
  t.write();
  CHECK_THROWS_WITH(load_dataset(t.root), Catch::Contains("ego_pose.json") && Catch::Contains("'e1'") &&
                                              Catch::Contains("quaternion has norm 0"));
  t.ego[0]["rotation"] = {0.0, 0.0, 0.0, 1.0};
  t.cal[0]["rotation"] = {2.0, 0.0, 0.0, 0.0};
  t.write();
  CHECK_THROWS_WITH(load_dataset(t.root), Catch::Contains("calibrated_sensor.json") && Catch::Contains("norm 2"));
}

TEST_CASE("nuScenes: JSON type errors name the table file", "[layout][bad-input]") {
  struct Case {
    std::string table;
    std::function<void(NuScenesTree&)> spoil;
    std::string key;
  };
  const std::vector<Case> cases = {
      {"sample_data.json", [](NuScenesTree& t) { t.sd[0]["token"] = 7; }, "'token'"},
      {"sample_data.json", [](NuScenesTree& t) { t.sd[0]["timestamp"] = "noon"; }, "'timestamp'"},
      {"sample_data.json", [](NuScenesTree& t) { t.sd[0]["is_key_frame"] = 1; }, "'is_key_frame'"},
      {"sample_data.json", [](NuScenesTree& t) { t.sd[0]["filename"] = 3; }, "'filename'"},
      {"sample_data.json", [](NuScenesTree& t) { t.sd[0]["sample_token"] = Json::array(); }, "'sample_token'"},
      {"sample.json", [](NuScenesTree& t) { t.sample[0]["scene_token"] = nullptr; }, "'scene_token'"},
      {"scene.json", [](NuScenesTree& t) { t.scene[0]["name"] = 916; }, "'name'"},
      {"sensor.json", [](NuScenesTree& t) { t.sensor[0]["channel"] = false; }, "'channel'"},
      {"calibrated_sensor.json", [](NuScenesTree& t) { t.cal[0]["sensor_token"] = 1.5; }, "'sensor_token'"},
      {"ego_pose.json", [](NuScenesTree& t) { t.ego[0]["translation"] = {1, "x", 2}; }, "'translation'"},
      {"ego_pose.json", [](NuScenesTree& t) { t.ego[0]["rotation"] = "identity"; }, "rotation[4]"},
  };
  int k = 0;
  for (const auto& c : cases) {
    NuScenesTree t("nus_type_" + std::to_string(k++));
    c.spoil(t);
    t.write();
    INFO(c.table << " " << c.key);
    CHECK_THROWS_AS(load_dataset(t.root), IoError);
    CHECK_THROWS_WITH(load_dataset(t.root), Catch::Contains(c.table) && Catch::Contains(c.key));
  }
}

TEST_CASE("sensors with gigabyte range images are refused", "[sensor][bad-input]") {
  Json j = sensor_to_json(sensor_preset("kitti360"));
  j["height"] = 4096;
  j["width"] = 65536;  // each bound alone was accepted: 3 GB of images per frame
  CHECK_THROWS_WITH(sensor_from_json(j, "big.json"), Catch::Contains("pixels per range image"));
  j["height"] = 128;
  j["width"] = 8192;  // 2^20: the largest accepted
  CHECK(sensor_from_json(j, "ok.json").width == 8192);
  j["width"] = 8193;
  CHECK_THROWS_AS(sensor_from_json(j, "big.json"), ConfigError);
}

TEST_CASE("test folders live under the build tree, not a fixed /tmp name", "[support]") {
  const std::string a = test::temp_dir("where");
  CHECK(a.rfind(std::string(SGNLF_TEST_TMP_DIR), 0) == 0);
  CHECK(a.find("/tmp/sgnlf-test-") == std::string::npos);
  CHECK(fs::is_directory(a));
}

TEST_CASE("a synthetic-layout folder says whether its reference poses are planar", "[layout][bad-input]") {
  // A twin: 3D reference. A window sgnlf bench copied from nuScenes: planar (horizontal ATE),
  // from the written key or, in folders written before it, from real_source.
  const std::string root = kitti360_tree("planar_reference", true);
  CHECK_FALSE(load_dataset(root).planar_reference);
  Json meta = load_json_file(root + "/sgnlf_dataset.json");
  meta["real_source"] = "nuscenes";
  write_json_file(root + "/sgnlf_dataset.json", meta);
  CHECK(load_dataset(root).planar_reference);
  meta["real_source"] = "kitti360";
  write_json_file(root + "/sgnlf_dataset.json", meta);
  CHECK_FALSE(load_dataset(root).planar_reference);
  meta["planar_reference"] = true;
  write_json_file(root + "/sgnlf_dataset.json", meta);
  CHECK(load_dataset(root).planar_reference);
  meta["planar_reference"] = "yes";
  write_json_file(root + "/sgnlf_dataset.json", meta);
  CHECK_THROWS_WITH(load_dataset(root),
                    Catch::Contains("sgnlf_dataset.json") && Catch::Contains("'planar_reference'"));
}
