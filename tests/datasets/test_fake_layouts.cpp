// Tiny fake trees in the KITTI-360 and nuScenes layouts (protocol §2): pose chains, frames
// without a pose, scene boundaries, and clear errors for missing calibration or tables.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/config.hpp"
#include "core/error.hpp"
#include "datasets/loader.hpp"
#include "io/scan_io.hpp"
#include "io/trajectory_io.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;
namespace fs = std::filesystem;

namespace {
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
Pose make_pose(double rz, double ry, Vec3 t) {
  Pose T = Pose::Identity();
  T.linear() = exp_so3(Vec3(0.01, ry, rz));
  T.translation() = t;
  return T;
}
std::vector<PointXYZI> scan(float shift) {
  return {{5.f + shift, 1.f, -1.f, 0.3f}, {-7.f, 2.f, 0.5f, 0.6f}, {2.f, -9.f, -1.5f, 0.1f}};
}

struct Kitti360Tree {
  std::string root;
  Pose T_imu_cam = make_pose(1.2, 0.05, Vec3(1.5, 0.2, 0.1)), T_velo_cam = make_pose(-1.5, 0.02, Vec3(0.3, -0.1, -0.05));
  std::map<int, Pose> imu;
  explicit Kitti360Tree(const std::string& name) : root(test::temp_dir(name)) {
    const std::string drive = "2013_05_28_drive_0000_sync";
    fs::create_directories(root + "/calibration");
    fs::create_directories(root + "/data_poses/" + drive);
    write_text_file(root + "/calibration/calib_cam_to_pose.txt", "image_00: " + pose12(T_imu_cam) + "\nimage_01: " + pose12(T_imu_cam) + "\n");
    write_text_file(root + "/calibration/calib_cam_to_velo.txt", pose12(T_velo_cam) + "\n");
    std::string poses;
    for (int id : {10, 11, 13, 14}) {  // frame 12 has no pose (vehicle standing)
      imu[id] = make_pose(0.1 * id, 0.0, Vec3(2.0 * id, 0.5 * id, 0.1));
      poses += std::to_string(id) + " " + pose12(imu[id]) + "\n";
    }
    write_text_file(root + "/data_poses/" + drive + "/poses.txt", poses);
    for (int id = 10; id <= 14; ++id) {
      char n[32];
      std::snprintf(n, sizeof(n), "/%010d.bin", id);
      io::write_kitti_bin(root + "/data_3d_raw/" + drive + "/velodyne_points/data" + n, scan(float(id)));
    }
  }
};
}  // namespace

TEST_CASE("KITTI-360 layout: pose chain and frames without a pose", "[layout]") {
  Kitti360Tree t("fake_kitti360");
  CHECK(detect_layout(t.root) == "kitti360");
  LoadOptions o;
  o.start = 10;
  o.frames = 4;
  const Dataset d = load_dataset(t.root, o);
  REQUIRE(d.frames.size() == 4);
  CHECK(d.frames[2].id == 13);  // 12 skipped
  CHECK(d.frames[2].points[0].x == 18.f);
  for (const auto& f : d.frames) {
    const Pose expect = t.imu.at(f.id) * t.T_imu_cam * t.T_velo_cam.inverse();
    CHECK((expect.matrix() - f.T_world_lidar.matrix()).norm() < 1e-12);
  }
  CHECK(d.frames[1].timestamp_s == Approx(0.1));  // no timestamps.txt: id / rate
  o.stride = 2;  // 10, 12 (no pose: skipped), 14
  CHECK(load_dataset(t.root, o).frames.size() == 2);
}

TEST_CASE("KITTI-360 layout: missing calibration, bad poses.txt", "[layout][bad-input]") {
  Kitti360Tree t("fake_kitti360_bad");
  LoadOptions o;
  o.start = 10;
  fs::remove(t.root + "/calibration/calib_cam_to_velo.txt");
  CHECK_THROWS_WITH(load_dataset(t.root, o), Catch::Contains("calib_cam_to_velo.txt") && Catch::Contains("missing"));
  Kitti360Tree u("fake_kitti360_bad2");
  write_text_file(u.root + "/data_poses/2013_05_28_drive_0000_sync/poses.txt",
                  "10 " + pose12(Pose::Identity()) + "\n11 1 0 0 0 0 1 0 0 0 0 1\n");
  CHECK_THROWS_WITH(load_dataset(u.root, o), Catch::Contains("poses.txt:2") && Catch::Contains("12 fields"));
  Kitti360Tree v("fake_kitti360_bad3");
  write_text_file(v.root + "/calibration/calib_cam_to_pose.txt", "image_01: " + pose12(Pose::Identity()) + "\n");
  CHECK_THROWS_WITH(load_dataset(v.root, o), Catch::Contains("calib_cam_to_pose.txt") && Catch::Contains("image_00"));
  CHECK_THROWS_WITH(load_dataset(test::temp_dir("fake_empty")), Catch::Contains("unknown dataset layout"));
}

namespace {
Json quat_pose(const std::string& token, double yaw, Vec3 t) {
  return Json{{"token", token}, {"rotation", {std::cos(yaw / 2), 0.0, 0.0, std::sin(yaw / 2)}}, {"translation", {t.x(), t.y(), t.z()}}};
}
Pose yaw_pose(double yaw, Vec3 t) {
  Pose T = Pose::Identity();
  T.linear() = exp_so3(Vec3(0, 0, yaw));
  T.translation() = t;
  return T;
}
std::string make_nuscenes(const std::string& name) {
  const std::string root = test::temp_dir(name), tdir = root + "/v1.0-mini";
  fs::create_directories(tdir);
  write_json_file(tdir + "/scene.json", Json::array({{{"token", "sc1"}, {"name", "scene-0001"}}, {{"token", "sc2"}, {"name", "scene-0002"}}}));
  write_json_file(tdir + "/sample.json", Json::array({{{"token", "s1"}, {"scene_token", "sc1"}}, {{"token", "s2"}, {"scene_token", "sc1"}},
                                                      {{"token", "s3"}, {"scene_token", "sc2"}}}));
  write_json_file(tdir + "/sensor.json", Json::array({{{"token", "lid"}, {"channel", "LIDAR_TOP"}}, {{"token", "cam"}, {"channel", "CAM_FRONT"}}}));
  Json c1 = quat_pose("c1", 1.5, Vec3(0.9, 0.0, 1.8)), c2 = quat_pose("c2", 0.0, Vec3(0, 0, 0));
  c1["sensor_token"] = "lid";
  c2["sensor_token"] = "cam";
  write_json_file(tdir + "/calibrated_sensor.json", Json::array({c1, c2}));
  Json ego = Json::array();
  for (int i = 0; i < 5; ++i) ego.push_back(quat_pose("e" + std::to_string(i), 0.2 * i, Vec3(10.0 * i, 1.0, 0.0)));
  write_json_file(tdir + "/ego_pose.json", ego);
  auto sd = [](const std::string& tok, const std::string& sample, const std::string& ego_tok, const std::string& cal,
               int64_t ts, bool key, const std::string& file) {
    return Json{{"token", tok}, {"sample_token", sample}, {"ego_pose_token", ego_tok}, {"calibrated_sensor_token", cal},
                {"timestamp", ts}, {"is_key_frame", key}, {"filename", file}};
  };
  write_json_file(tdir + "/sample_data.json",
                  Json::array({sd("d1", "s1", "e1", "c1", 3000000, true, "samples/LIDAR_TOP/b.pcd.bin"),
                               sd("d2", "s2", "e2", "c1", 2000000, true, "samples/LIDAR_TOP/a.pcd.bin"),
                               sd("d3", "s2", "e3", "c1", 2500000, false, "sweeps/LIDAR_TOP/c.pcd.bin"),
                               sd("d4", "s3", "e4", "c1", 9000000, true, "samples/LIDAR_TOP/d.pcd.bin"),
                               sd("d5", "s1", "e0", "c2", 3000000, true, "samples/CAM_FRONT/x.jpg")}));
  int k = 0;
  for (const std::string f : {"samples/LIDAR_TOP/a.pcd.bin", "samples/LIDAR_TOP/b.pcd.bin", "sweeps/LIDAR_TOP/c.pcd.bin", "samples/LIDAR_TOP/d.pcd.bin"}) {
    std::vector<float> v = {float(3 + k), 1, -1, 102, 5, -6, 2, 0.5f, 255, 20};
    fs::create_directories(fs::path(root + "/" + f).parent_path());
    io::write_file_bytes(root + "/" + f, v.data(), v.size() * 4);
    ++k;
  }
  return root;
}
}  // namespace

TEST_CASE("nuScenes layout: LIDAR_TOP records, timestamp order, scenes, pose chain", "[layout]") {
  const std::string root = make_nuscenes("fake_nuscenes");
  CHECK(detect_layout(root) == "nuscenes");
  const Dataset low = load_dataset(root);  // default: low frequency (keyframes), first scene
  CHECK(low.name == "scene-0001");
  CHECK(low.planar_reference);  // ego poses with z = 0: judged by the horizontal ATE
  REQUIRE(low.frames.size() == 2);
  CHECK(low.frames[0].points[0].x == 3.f);  // a.pcd.bin (earlier timestamp) first
  CHECK(low.frames[0].points[0].intensity == Approx(0.4));
  CHECK(low.frames[1].timestamp_s == Approx(1.0));
  const Pose expect = yaw_pose(0.4, Vec3(20, 1, 0)) * yaw_pose(1.5, Vec3(0.9, 0, 1.8));  // ego e2 · calib c1
  CHECK((low.frames[0].T_world_lidar.matrix() - expect.matrix()).norm() < 1e-9);
  LoadOptions o;
  o.frequency = "standard";  // sweeps too
  const Dataset all = load_dataset(root, o);
  REQUIRE(all.frames.size() == 3);
  CHECK(all.frames[1].points[0].x == 5.f);  // the sweep between the two keyframes
  o.sequence = "scene-0002";
  CHECK(load_dataset(root, o).frames.size() == 1);  // a window never crosses a scene
  o.sequence = "scene-0404";
  CHECK_THROWS_WITH(load_dataset(root, o), Catch::Contains("scene-0404"));
}

TEST_CASE("nuScenes layout: missing table or record", "[layout][bad-input]") {
  const std::string root = make_nuscenes("fake_nuscenes_bad");
  fs::remove(root + "/v1.0-mini/ego_pose.json");
  CHECK_THROWS_WITH(load_dataset(root), Catch::Contains("ego_pose.json") && Catch::Contains("missing nuScenes table"));
  const std::string r2 = make_nuscenes("fake_nuscenes_bad2");
  write_json_file(r2 + "/v1.0-mini/ego_pose.json", Json::array({quat_pose("e0", 0, Vec3(0, 0, 0))}));
  CHECK_THROWS_WITH(load_dataset(r2), Catch::Contains("ego_pose.json") && Catch::Contains("no record with token"));
}

TEST_CASE("KITTI odometry layout: too few pose rows, missing Tr", "[layout][bad-input]") {
  const std::string root = test::temp_dir("fake_odometry");
  fs::create_directories(root + "/poses");
  fs::create_directories(root + "/sequences/07");
  write_text_file(root + "/sequences/07/calib.txt", "P0: 1 0 0 0 0 1 0 0 0 0 1 0\nTr: " + pose12(make_pose(-1.5, 0.01, Vec3(0.1, 0, -0.1))) + "\n");
  write_text_file(root + "/poses/07.txt", pose12(Pose::Identity()) + "\n" + pose12(make_pose(0, 0, Vec3(0, 0, 1))) + "\n");
  for (int id = 0; id < 2; ++id) {
    char n[32];
    std::snprintf(n, sizeof(n), "/%06d.bin", id);
    io::write_kitti_bin(root + "/sequences/07/velodyne" + n, scan(float(id)));
  }
  CHECK(detect_layout(root) == "kitti-odometry");
  const Dataset d = load_dataset(root);
  REQUIRE(d.frames.size() == 2);
  CHECK((d.frames[1].T_world_lidar.translation() - d.frames[0].T_world_lidar.translation()).norm() == Approx(1.0));
  io::write_kitti_bin(root + "/sequences/07/velodyne/000002.bin", scan(2.f));  // a scan without a pose row
  CHECK_THROWS_WITH(load_dataset(root), Catch::Contains("07.txt") && Catch::Contains("2 pose rows"));
  write_text_file(root + "/sequences/07/calib.txt", "P0: 1 0 0 0 0 1 0 0 0 0 1 0\n");
  CHECK_THROWS_WITH(load_dataset(root), Catch::Contains("calib.txt") && Catch::Contains("'Tr'"));
}
