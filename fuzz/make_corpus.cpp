// Writes the seed corpus of every fuzz target (fuzz/corpus/<target>/) with the project's own
// writers: scans (io::write_kitti_bin, write_file_bytes, write_pcd, write_ply), trajectories (write_kitti_poses,
// write_tum_poses, write_indexed_poses), calibration lines in the loaders' layout, sensor and
// load-option JSON (sensor_to_json, LoadOptions::to_json), checkpoints (save_checkpoint),
// .npy (write_range_npy), nuScenes tables (write_json_file) and a trimmed smoke result for
// compare. Usage: fuzz_make_corpus OUT_DIR SMOKE_RESULTS_JSON
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/config.hpp"
#include "datasets/loader.hpp"
#include "geometry/sensor.hpp"
#include "io/cloud_writers.hpp"
#include "io/range_array.hpp"
#include "io/scan_io.hpp"
#include "io/trajectory_io.hpp"
#include "pipeline/train/checkpoint.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/config/train_config.hpp"

using namespace sgnlf;
namespace fs = std::filesystem;

namespace {

std::string read_all(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Seeds whose first byte selects a reader: the prefix byte, then the file.
void seed(const std::string& dir, const std::string& name, const std::string& bytes, int prefix = -1) {
  fs::create_directories(dir);
  std::ofstream out(dir + "/" + name, std::ios::binary | std::ios::trunc);
  if (prefix >= 0) out.put(char(prefix));
  out << bytes;
}

Pose pose(double yaw, double x) {
  Pose T = Pose::Identity();
  T.linear() = exp_so3(Vec3(0.01, 0.02, yaw));
  T.translation() = Vec3(x, 0.5 * x, 0.1);
  return T;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s OUT_DIR SMOKE_RESULTS_JSON\n", argv[0]);
    return 2;
  }
  const std::string out = argv[1], tmp = out + "/.tmp";
  fs::create_directories(tmp);

  // Scans.
  std::vector<PointXYZI> pts = {{5.f, 1.f, -1.f, 0.3f}, {-7.f, 2.f, 0.5f, 0.6f}, {2.f, -9.f, -1.5f, 0.1f}};
  io::write_kitti_bin(tmp + "/a.bin", pts);
  seed(out + "/fuzz_scan_kitti", "three_points.bin", read_all(tmp + "/a.bin"));
  const std::vector<float> nus = {3, 1, -1, 102, 5, -6, 2, 0.5f, 255, 20};
  io::write_file_bytes(tmp + "/a.pcd.bin", nus.data(), nus.size() * 4);
  seed(out + "/fuzz_scan_nuscenes", "two_points.pcd.bin", read_all(tmp + "/a.pcd.bin"));

  // PCD and PLY scans of 24 points (exact binary fractions: the same bytes on every libm), in
  // every encoding, with and without ring and time; one hand-written file each for the header
  // forms the writers do not produce (v0.6 PCD with COUNT 3; PLY faces around the vertices).
  std::vector<PointXYZI> scan;
  io::ScanExtras ex;
  for (int k = 0; k < 24; ++k) {
    scan.push_back({0.5f * float(k) - 6.f, 1.25f * float(k % 5), -1.5f + 0.125f * float(k % 3), 10.f * float(k)});
    ex.ring.push_back(k % 16);
    ex.time.push_back(0.00390625 * k);
  }
  ex.has_ring = ex.has_time = ex.has_intensity = true;
  const std::string pcd = out + "/fuzz_scan_pcd", ply = out + "/fuzz_scan_ply";
  const std::pair<io::PcdEncoding, const char*> pcd_enc[] = {
      {io::PcdEncoding::kAscii, "ascii"}, {io::PcdEncoding::kBinary, "binary"}, {io::PcdEncoding::kBinaryCompressed, "compressed"}};
  for (const auto& [enc, name] : pcd_enc) {
    io::write_pcd(tmp + "/s.pcd", scan, enc);
    seed(pcd, std::string(name) + ".pcd", read_all(tmp + "/s.pcd"));
    io::write_pcd(tmp + "/s.pcd", scan, enc, &ex);
    seed(pcd, std::string(name) + "_ring_time.pcd", read_all(tmp + "/s.pcd"));
  }
  seed(pcd, "v06_count3.pcd",
       "# .PCD v0.6\nFIELDS rgb x normal y z\nSIZE 4 4 4 4 4\nTYPE U F F F F\nCOUNT 1 1 3 1 1\nWIDTH 2\n"
       "HEIGHT 1\nDATA ascii\n7 1.5 0 0 1 2 -3\n9 nan 0 1 0 4 5\n");
  const std::pair<io::PlyEncoding, const char*> ply_enc[] = {{io::PlyEncoding::kAscii, "ascii"},
                                                             {io::PlyEncoding::kBinaryLittleEndian, "little"},
                                                             {io::PlyEncoding::kBinaryBigEndian, "big"}};
  for (const auto& [enc, name] : ply_enc) {
    io::write_ply(tmp + "/s.ply", scan, enc);
    seed(ply, std::string(name) + ".ply", read_all(tmp + "/s.ply"));
    io::write_ply(tmp + "/s.ply", scan, enc, &ex);
    seed(ply, std::string(name) + "_ring_time.ply", read_all(tmp + "/s.ply"));
  }
  seed(ply, "faces_around_vertices.ply",
       "ply\nformat ascii 1.0\ncomment faces before and after\nelement face 1\nproperty list uchar int vertex_index\n"
       "element vertex 3\nproperty short x\nproperty uint16 y\nproperty double z\nproperty uchar reflectance\n"
       "property list uchar float n\nelement edge 1\nproperty int a\nproperty int b\nend_header\n"
       "3 0 1 2\n1 2 3 200 0\n-4 5 6.5 17 2 0.5 0.25\n7 8 9 255 1 1\n0 2\n");

  // Trajectories: prefix 0 KITTI, 1 TUM, 2 KITTI-360 poses.txt.
  const std::vector<Pose> poses = {pose(0.0, 0.0), pose(0.1, 1.0), pose(0.25, 2.5)};
  io::write_kitti_poses(tmp + "/k.txt", poses);
  io::write_tum_poses(tmp + "/t.txt", {0.0, 0.1, 0.2}, poses);
  io::write_indexed_poses(tmp + "/i.txt", {3, 4, 7}, poses);
  seed(out + "/fuzz_poses", "kitti.txt", read_all(tmp + "/k.txt"), 0);
  seed(out + "/fuzz_poses", "tum.txt", read_all(tmp + "/t.txt"), 1);
  seed(out + "/fuzz_poses", "kitti360.txt", read_all(tmp + "/i.txt"), 2);

  // Calibrations as the loaders expect them: a 3×4 rigid matrix under each key.
  double v[12];
  pose_to_3x4(pose(1.2, 0.3), v);
  std::string m;
  for (int k = 0; k < 12; ++k) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v[k]);
    m += (k ? " " : "") + std::string(b);
  }
  seed(out + "/fuzz_calibration", "cam_to_pose.txt", "image_00: " + m + "\nimage_01: " + m + "\n");
  seed(out + "/fuzz_calibration", "cam_to_velo.txt", m + "\n");
  seed(out + "/fuzz_calibration", "odometry_calib.txt", "P0: 7 0 6 0 0 7 1 0 0 0 1 0\nTr: " + m + "\n");

  // JSON for the strict loader: prefix 0 sensor, 1 load options, 2 sgnlf_dataset.json.
  seed(out + "/fuzz_config_json", "sensor_kitti360.json", sensor_to_json(sensor_preset("kitti360")).dump(2), 0);
  seed(out + "/fuzz_config_json", "sensor_preset.json", Json{{"preset", "nuscenes"}, {"width", 512}}.dump(2), 0);
  LoadOptions lo;
  lo.sequence = "00";
  lo.start = 3;
  lo.frames = 8;
  lo.stride = 2;
  lo.test_frames = {1, 5};
  seed(out + "/fuzz_config_json", "load_options.json", lo.to_json().dump(2), 1);
  seed(out + "/fuzz_config_json", "sgnlf_dataset.json",
       Json{{"name", "fuzz"}, {"sequence", "2013_05_28_drive_0000_sync"}, {"frequency", "standard"},
            {"first_frame", 0}, {"stride", 1}, {"frames", 4}}.dump(2), 2);

  // Checkpoint: after byte 0x01 (the target fixes the checksum up), and as written.
  pipeline::Checkpoint ck;
  ck.step = 20;
  ck.seed = 1;
  ck.config_hash = 0x1234;
  ck.arrays = {{"params", {0.5f, -1.f, 2.f}}, {"adam_m", {0.f, 0.f, 0.f}}, {"pose_xi", pipeline::pack_doubles({0.1, 0.2})}};
  pipeline::save_checkpoint(tmp + "/c.ckpt", ck);
  seed(out + "/fuzz_checkpoint", "small.ckpt", read_all(tmp + "/c.ckpt"), 1);
  seed(out + "/fuzz_checkpoint", "small_as_written.ckpt", read_all(tmp + "/c.ckpt"));

  // .npy range image.
  RangeImage img(2, 3);
  for (size_t i = 0; i < img.size(); ++i) {
    img.range[i] = 1.f + float(i);
    img.intensity[i] = 0.1f * float(i);
    img.ray_drop[i] = float(i % 2);
  }
  io::write_range_npy(tmp + "/r.npy", img);
  seed(out + "/fuzz_npy", "2x3.npy", read_all(tmp + "/r.npy"));

  // nuScenes tables: prefix = which table (0 sample_data, 1 ego_pose, 2 calibrated_sensor,
  // 3 sample, 4 scene, 5 sensor), as fuzz_nuscenes_tables writes the valid ones.
  auto q = [](const std::string& tok, double w, double z) {
    return Json{{"token", tok}, {"rotation", {w, 0.0, 0.0, z}}, {"translation", {1.0, 2.0, 0.5}}};
  };
  Json cal = Json::array({q("c1", 1.0, 0.0)});
  cal[0]["sensor_token"] = "lid";
  Json sd = Json::array();
  for (int k = 0; k < 2; ++k)
    sd.push_back({{"token", "d" + std::to_string(k)}, {"sample_token", "s1"}, {"ego_pose_token", "e" + std::to_string(k)},
                  {"calibrated_sensor_token", "c1"}, {"timestamp", 1000000 + 500000 * k}, {"is_key_frame", k == 0},
                  {"filename", "samples/LIDAR_TOP/a.pcd.bin"}});
  const std::vector<Json> tables = {sd, Json::array({q("e0", 0.0, 1.0), q("e1", 1.0, 0.0)}), cal,
                                    Json::array({{{"token", "s1"}, {"scene_token", "sc1"}}}),
                                    Json::array({{{"token", "sc1"}, {"name", "scene-0001"}}}),
                                    Json::array({{{"token", "lid"}, {"channel", "LIDAR_TOP"}}})};
  const char* names[] = {"sample_data", "ego_pose", "calibrated_sensor", "sample", "scene", "sensor"};
  for (int k = 0; k < 6; ++k) {
    write_json_file(tmp + "/t.json", tables[size_t(k)]);
    seed(out + "/fuzz_nuscenes_tables", std::string(names[k]) + ".json", read_all(tmp + "/t.json"), k);
  }

  // Results for compare: the smoke result trimmed to its first row and sequence (the target
  // compares with the whole baseline), as new (prefix 0) and as baseline (prefix 1).
  Json res = load_json_file(argv[2]);
  Json row = res["rows"][0];
  row["sequences"] = Json::array({row["sequences"][0]});
  row["sequences"][0].erase("per_frame");
  row["sequences"][0].erase("config");
  res["rows"] = Json::array({row});
  res.erase("paper");
  write_json_file(tmp + "/res.json", res);
  seed(out + "/fuzz_compare_results", "smoke_first_row.json", read_all(tmp + "/res.json"), 0);
  seed(out + "/fuzz_compare_results", "smoke_first_row_as_baseline.json", read_all(tmp + "/res.json"), 1);

  // Training configs: overrides onto a preset (the prefix byte picks it: 2·k for the k-th of
  // preset_names()) and whole configs as run.json holds them (odd prefix).
  const std::vector<std::string> presets = pipeline::preset_names();
  auto preset_prefix = [&](const std::string& name) {
    for (size_t k = 0; k < presets.size(); ++k)
      if (presets[k] == name) return int(2 * k);
    throw Error("make_corpus: no preset " + name);
  };
  const std::string tc = out + "/fuzz_train_config";
  seed(tc, "overrides_schedule.json", Json{{"schedule", {{"iterations", 10}, {"rays_per_batch", 256}}}}.dump(1),
       preset_prefix("lidar-nerf-smoke"));
  seed(tc, "overrides_poses_odometry.json", Json{{"poses", {{"init", "odometry"}}}}.dump(1),
       preset_prefix("geonlf-quick"));
  seed(tc, "overrides_spectral.json",
       Json{{"spectral", {{"psi", {{"k", 8}, {"activation", "sine"}}}, {"fusion", {{"start", 10}, {"end", 20}}}}}}.dump(1),
       preset_prefix("sg-nlf-smoke"));
  seed(tc, "whole_sg_nlf_quick.json",
       pipeline::train_config_to_json(pipeline::resolve_config("sg-nlf", "quick")).dump(1), 1);
  seed(tc, "whole_lidar_nerf_paper.json",
       pipeline::train_config_to_json(pipeline::resolve_config("lidar-nerf", "paper")).dump(1), 1);

  fs::remove_all(tmp);
  return 0;
}
