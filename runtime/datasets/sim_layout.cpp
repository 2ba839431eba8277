// write_synthetic (see simulate.hpp): the KITTI-360-like layout of a simulated sequence.
#include <cstdio>
#include <filesystem>

#include "datasets/actor_truth.hpp"
#include "datasets/simulate.hpp"
#include "io/scan_io.hpp"
#include "io/trajectory_io.hpp"

namespace sgnlf {
namespace fs = std::filesystem;

namespace {
// Fixed extrinsics of the synthetic car, shaped like KITTI-360's (camera axes: x right,
// y down, z forward; LiDAR and IMU: x forward, y left, z up).
Pose cam_to_velo() {
  Pose T = Pose::Identity();
  T.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;  // columns: camera axes in LiDAR coordinates
  T.linear() = T.linear() * exp_so3(Vec3(0.004, -0.012, 0.002));
  T.translation() = Vec3(0.27, -0.01, -0.08);
  return T;  // T_velo_cam: maps camera points into the LiDAR frame
}
Pose cam_to_pose() {
  Pose T = Pose::Identity();
  T.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  T.linear() = T.linear() * exp_so3(Vec3(-0.03, 0.01, 0.005));
  T.translation() = Vec3(1.55, -0.3, 0.05);
  return T;
}
std::string pose12(const Pose& T) {
  double v[12];
  pose_to_3x4(T, v);
  std::string s;
  char b[40];
  for (int k = 0; k < 12; ++k) { std::snprintf(b, sizeof(b), "%.17g", v[k]); s += (k ? " " : "") + std::string(b); }
  return s;
}
}  // namespace

void write_synthetic(const SimResult& r, const std::string& dir) {
  const Dataset& d = r.dataset;
  const std::string seq = r.metadata.at("sequence").get<std::string>();
  const fs::path root(dir);
  fs::create_directories(root / "calibration");
  // calib_cam_to_velo.txt stores the camera → LiDAR transform (it maps camera points into
  // the LiDAR frame, i.e. T_velo_cam); calib_cam_to_pose.txt stores T_imu_cam.
  const Pose T_velo_cam = cam_to_velo(), T_imu_cam = cam_to_pose();
  write_text_file((root / "calibration" / "calib_cam_to_velo.txt").string(), pose12(T_velo_cam) + "\n");
  write_text_file((root / "calibration" / "calib_cam_to_pose.txt").string(),
                  "image_00: " + pose12(T_imu_cam) + "\nimage_01: " + pose12(T_imu_cam) + "\n");
  const Pose T_lidar_imu = (T_imu_cam * T_velo_cam.inverse()).inverse();
  std::vector<int> ids;
  std::vector<Pose> imu_poses, lidar_poses;
  std::vector<double> stamps;
  std::string ts;
  const fs::path scan_dir = root / "data_3d_raw" / seq / "velodyne_points" / "data";
  fs::create_directories(scan_dir);
  fs::create_directories(root / "data_poses" / seq);
  for (const auto& f : d.frames) {
    ids.push_back(f.id);
    imu_poses.push_back(f.T_world_lidar * T_lidar_imu);  // imu_to_world
    lidar_poses.push_back(f.T_world_lidar);
    stamps.push_back(f.timestamp_s);
    char name[32];
    std::snprintf(name, sizeof(name), "%010d.bin", f.id);
    io::write_kitti_bin((scan_dir / name).string(), f.points);
  }
  // timestamps.txt has one line per native frame (KITTI-360 format, a fixed synthetic date).
  const int last = d.frames.back().id;
  for (int id = 0; id <= last; ++id) {
    const double t = id / d.sensor.rate_hz;
    char b[64];
    std::snprintf(b, sizeof(b), "2013-05-28 08:%02d:%012.9f\n", int(t / 60.0), std::fmod(t, 60.0));
    ts += b;
  }
  write_text_file((scan_dir.parent_path() / "timestamps.txt").string(), ts);
  io::write_indexed_poses((root / "data_poses" / seq / "poses.txt").string(), ids, imu_poses);
  fs::create_directories(root / "ground_truth");
  io::write_kitti_poses((root / "ground_truth" / "T_world_lidar.txt").string(), lidar_poses);
  io::write_tum_poses((root / "ground_truth" / "T_world_lidar.tum").string(), stamps, lidar_poses);
  write_json_file((root / "sensor.json").string(), sensor_to_json(d.sensor));
  if (!r.actors.empty()) write_actor_truth(dir, r.actors, r.actor_clock_offset_s, d.frames);
  write_json_file((root / "sgnlf_dataset.json").string(), r.metadata);
}

}  // namespace sgnlf
