#include "datasets/simulate.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/progress.hpp"
#include "datasets/protocol.hpp"
#include "datasets/sim_street.hpp"
#include "io/scan_io.hpp"
#include "io/trajectory_io.hpp"

namespace sgnlf {
namespace fs = std::filesystem;

const std::vector<NamedSequence>& named_sequences() {
  static const std::vector<NamedSequence> seqs = {
      {"kitti360-1538", "kitti360", "standard", "street", 64, 0, "standard frequency, twin of KITTI-360 start 1538"},
      {"kitti360-1728", "kitti360", "standard", "street", 64, 0, "standard frequency, twin of KITTI-360 start 1728"},
      {"kitti360-1908", "kitti360", "standard", "street", 64, 0, "standard frequency, twin of KITTI-360 start 1908"},
      {"kitti360-3353", "kitti360", "standard", "street", 64, 0, "standard frequency, twin of KITTI-360 start 3353"},
      {"kitti360-low-a", "kitti360", "low", "street", 36, 0, "low frequency (2 Hz), street with turns"},
      {"kitti360-low-b", "kitti360", "low", "street", 36, 0, "low frequency (2 Hz), street with turns"},
      {"kitti360-low-c", "kitti360", "low", "street", 36, 0, "low frequency (2 Hz), street with turns"},
      {"kitti360-low-d", "kitti360", "low", "street", 36, 0, "low frequency (2 Hz), street with turns"},
      {"kitti360-loop", "kitti360", "low", "loop", 36, 0, "low frequency, drives around a block and revisits its start"},
      {"kitti360-dynamic", "kitti360", "standard", "street", 64, 6, "standard frequency with moving vehicles"},
      {"nuscenes-low-a", "nuscenes", "low", "street", 36, 0, "nuScenes-like, 2 Hz keyframes"},
      {"nuscenes-low-b", "nuscenes", "low", "street", 36, 0, "nuScenes-like, 2 Hz keyframes"},
      {"nuscenes-low-c", "nuscenes", "low", "street", 36, 0, "nuScenes-like, 2 Hz keyframes"},
      {"nuscenes-loop", "nuscenes", "low", "loop", 36, 0, "nuScenes-like loop around a block"},
      {"nuscenes-dynamic", "nuscenes", "low", "street", 36, 6, "nuScenes-like with moving vehicles"},
  };
  return seqs;
}

const NamedSequence& find_sequence(const std::string& name) {
  std::string known;
  for (const auto& s : named_sequences()) {
    if (s.name == name) return s;
    known += (known.empty() ? "" : ", ") + s.name;
  }
  throw ConfigError("unknown synthetic sequence '" + name + "' (known: " + known + ")");
}

Json named_sequences_json() {
  Json a = Json::array();
  for (const auto& s : named_sequences())
    a.push_back(Json{{"name", s.name}, {"preset", s.preset}, {"frequency", s.frequency}, {"layout", s.layout},
                     {"frames", s.frames}, {"moving_vehicles", s.moving_vehicles}, {"description", s.description}});
  return a;
}

void SimOptions::validate() const {
  find_sequence(sequence);
  if (!frequency.empty() && frequency != "standard" && frequency != "low")
    throw ConfigError("simulate: frequency '" + frequency + "' (expected standard or low)");
  if (frames == 0 || frames < -1 || frames > 100000) throw ConfigError("simulate: frames = " + std::to_string(frames));
  if (width == 0 || width < -1) throw ConfigError("simulate: width = " + std::to_string(width));
  if (height == 0 || height < -1) throw ConfigError("simulate: height = " + std::to_string(height));
}

SimResult simulate(const SimOptions& opt) {
  opt.validate();
  const NamedSequence& ns = find_sequence(opt.sequence);
  const std::string preset = opt.preset.empty() ? ns.preset : opt.preset;
  Sensor sensor = opt.sensor_json.empty() ? sensor_preset(preset)
                                          : sensor_from_json(load_json_file(opt.sensor_json), opt.sensor_json);
  if (opt.width > 0) sensor.width = opt.width;
  if (opt.height > 0) sensor.height = opt.height;
  sensor.validate();
  const std::string freq = opt.frequency.empty() ? ns.frequency : opt.frequency;
  const int n = opt.frames > 0 ? opt.frames : (freq == "low" ? 36 : 64);
  const int stride = freq == "low" ? std::max(1, int(std::lround(sensor.rate_hz / 2.0))) : 1;  // 2 Hz
  const int movers = opt.moving_vehicles >= 0 ? opt.moving_vehicles : ns.moving_vehicles;
  const uint64_t world_seed = fnv1a64(ns.name + "#" + std::to_string(opt.seed));
  const bool nus = preset == "nuscenes";

  sim::DriveConfig dc;
  dc.seed = world_seed;
  dc.v_min = nus ? 3.0 : 5.0;
  dc.v_max = nus ? 8.0 : 10.0;
  if (ns.layout == "loop") { dc.v_min = 10.0; dc.v_max = 12.0; }  // around the block and back
  dc.sensor_height_m = nus ? 1.84 : 1.73;
  std::vector<double> times;
  std::vector<int> ids;
  for (int k = 0; k < n; ++k) {
    ids.push_back(k * stride);
    times.push_back(k * stride / sensor.rate_hz);
  }
  sim::LidarModel lidar = opt.lidar;
  if (nus) lidar.intensity_gain *= 0.3;  // real nuScenes LIDAR_TOP: mean intensity 0.074 after / 255
  sim::StreetConfig sc;
  sc.layout = ns.layout;
  sc.seed = world_seed;
  sc.moving_vehicles = movers;
  sc.drive_length_m = times.back() * dc.v_max + 10.0;
  sim::StreetWorld world = sim::generate_street(sc);
  const auto poses = sim::drive(world, dc, times);

  SimResult res;
  Dataset& d = res.dataset;
  d.name = ns.name;
  d.source = "synthetic";
  d.frequency = freq;
  d.sensor = sensor;
  Progress prog("simulate " + ns.name, n);
  std::vector<Json> per_frame;
  double image_drop = 0;
  for (int k = 0; k < n; ++k) {
    world.place_movers(times[size_t(k)]);
    Frame f;
    f.id = ids[size_t(k)];
    f.timestamp_s = times[size_t(k)];
    f.T_world_lidar = poses[size_t(k)];
    sim::DropStats st;
    f.points = sim::cast_scan(world.scene, sensor, f.T_world_lidar, lidar, world_seed, uint32_t(f.id),
                              opt.threads, &st);
    ProjectionStats ps;
    f.image = project_points(sensor, f.points, &ps);
    res.drops.add(st);
    const double img_drop = 1.0 - double(ps.projected) / double(f.image.size());
    image_drop += img_drop / n;
    per_frame.push_back(Json{{"frame", f.id}, {"points", f.points.size()}, {"ray_drop_rate", st.drop_rate()},
                             {"image_drop_rate", img_drop}});
    d.frames.push_back(std::move(f));
    prog.update(k + 1);
  }
  prog.finish();
  d.split = protocol_split(n, freq);
  const auto& D = res.drops;
  res.metadata = Json{
      {"format", "sgnlf-synthetic"}, {"version", 1}, {"name", ns.name}, {"sequence", ns.name + "_sync"},
      {"preset", preset}, {"frequency", freq}, {"layout", ns.layout}, {"seed", opt.seed},
      {"world_seed", hex64(world_seed)}, {"first_frame", 0}, {"stride", stride}, {"frames", n},
      {"moving_vehicles", movers}, {"description", ns.description},
      {"scene", {{"primitives", world.scene.primitives().size()}, {"road_half_width_m", world.road_half_width},
                 {"sidewalk_width_m", world.sidewalk_width}, {"path_length_m", world.path.length()},
                 {"closed_path", world.path.closed}}},
      {"beams", opt.lidar.beams},
      {"ray_drop", {{"image_drop_rate", image_drop}, {"rays", D.rays}, {"returns", D.returns}, {"drop_rate", D.drop_rate()}, {"ego", D.ego},
                    {"no_hit", D.no_hit}, {"out_of_range", D.out_of_range}, {"grazing", D.grazing},
                    {"weak", D.weak}, {"specular", D.specular}, {"random", D.random}}},
      {"per_frame", per_frame}};
  log::info("simulated ", ns.name, ": ", n, " frames, ", D.rays, " rays, ray drop rate ", D.drop_rate(),
            ", range-image drop rate ", image_drop);
  return res;
}

Dataset simulate_dataset(const SimOptions& opt) { return simulate(opt).dataset; }

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
  write_json_file((root / "sgnlf_dataset.json").string(), r.metadata);
}

}  // namespace sgnlf
