// KITTI-360 raw (and the synthetic layout, which mimics it) and KITTI odometry loaders
// (protocol §2 pose chains).
#include <algorithm>
#include <climits>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "datasets/actor_truth.hpp"
#include "datasets/loader_internal.hpp"
#include "datasets/protocol.hpp"
#include "io/trajectory_io.hpp"

namespace sgnlf::detail {
namespace fs = std::filesystem;

namespace {

std::string frame_file(const fs::path& dir, int id, int digits, const std::string& ext) {
  char b[32];
  std::snprintf(b, sizeof(b), "%0*d", digits, id);
  return (dir / (std::string(b) + ext)).string();
}

std::vector<int> scan_ids(const fs::path& dir, const std::string& ext) {
  if (!fs::is_directory(dir)) throw IoError(dir.string() + ": missing scan folder");
  std::vector<int> ids;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n.size() <= ext.size() || n.compare(n.size() - ext.size(), ext.size(), ext) != 0) continue;
    const std::string stem = n.substr(0, n.size() - ext.size());
    if (stem.find_first_not_of("0123456789") != std::string::npos) continue;
    // Frame numbers are ints; a longer digit string would overflow (std::stoi threw without
    // naming the file).
    const size_t nz = std::min(stem.find_first_not_of('0'), stem.size());
    long long id = 0;
    for (size_t k = nz; k < stem.size() && id <= INT_MAX; ++k) id = id * 10 + (stem[k] - '0');
    if (stem.size() - nz > 10 || id > INT_MAX)
      throw IoError(e.path().string() + ": frame number in the file name is out of range (at most " +
                    std::to_string(INT_MAX) + ")");
    ids.push_back(int(id));
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

// KITTI-360 velodyne timestamps.txt: "YYYY-MM-DD HH:MM:SS.fffffffff", line k = frame k.
std::map<int, double> read_kitti360_timestamps(const fs::path& file) {
  std::map<int, double> t;
  std::ifstream f(file);
  if (!f) return t;
  std::string l;
  for (int k = 0; std::getline(f, l); ++k) {
    int y, mo, d, h, mi;
    double s;
    if (std::sscanf(l.c_str(), "%d-%d-%d %d:%d:%lf", &y, &mo, &d, &h, &mi, &s) != 6)
      throw IoError(file.string() + ":" + std::to_string(k + 1) + ": bad timestamp '" + l + "'");
    t[k] = d * 86400.0 + h * 3600.0 + mi * 60.0 + s;
  }
  return t;
}

std::string meta_string(const Json& meta, const std::string& key, const std::string& where) {
  const Json& v = meta.at(key);
  if (!v.is_string()) throw IoError(where + ": key '" + key + "' must be a string, found " + v.dump());
  return v.get<std::string>();
}

// Whether a synthetic-layout folder's reference poses are planar (Dataset::planar_reference):
// "planar_reference" when written, else a window that sgnlf bench copied from nuScenes.
bool meta_planar_reference(const Json& meta, const std::string& where) {
  if (meta.contains("planar_reference")) {
    const Json& v = meta.at("planar_reference");
    if (!v.is_boolean())
      throw IoError(where + ": key 'planar_reference' must be true or false, found " + v.dump());
    return v.get<bool>();
  }
  return meta.contains("real_source") && meta_string(meta, "real_source", where) == "nuscenes";
}

int meta_int(const Json& meta, const std::string& key, int min, const std::string& where) {
  const Json& v = meta.at(key);
  if (!v.is_number_integer() || v.get<long long>() < min || v.get<long long>() > INT_MAX)
    throw IoError(where + ": key '" + key + "' must be an integer >= " + std::to_string(min) +
                  ", found " + v.dump());
  return int(v.get<long long>());
}

std::string pick_drive(const fs::path& root, const std::string& requested) {
  if (!requested.empty()) {
    for (const std::string& c : {requested, requested + "_sync"})
      if (fs::exists(root / "data_poses" / c)) return c;
    throw IoError((root / "data_poses" / requested).string() + ": no such sequence");
  }
  const std::string def = "2013_05_28_drive_0000_sync";
  if (fs::exists(root / "data_poses" / def)) return def;
  std::vector<std::string> drives;
  if (fs::is_directory(root / "data_poses"))
    for (const auto& e : fs::directory_iterator(root / "data_poses")) drives.push_back(e.path().filename().string());
  std::sort(drives.begin(), drives.end());
  if (drives.empty()) throw IoError((root / "data_poses").string() + ": missing pose folder (no sequence)");
  return drives.front();
}

// A sequence's own test frames (sgnlf_dataset.json "test_frame_ids", e.g. the dynamic split)
// replace the protocol split: the loaded frames among them are the test frames. A window
// holding none of them (or only them) keeps the protocol split, with a warning.
void apply_test_frame_ids(Dataset& d, const Json& meta, const std::string& where) {
  const Json& v = meta.at("test_frame_ids");
  if (!v.is_array()) throw IoError(where + ": key 'test_frame_ids' must be an array of frame ids");
  std::vector<int> ids;
  for (const auto& x : v) {
    if (!x.is_number_integer()) throw IoError(where + ": key 'test_frame_ids' holds " + x.dump() + ", not a frame id");
    ids.push_back(x.get<int>());
  }
  Split s;
  for (int i = 0; i < int(d.frames.size()); ++i)
    (std::find(ids.begin(), ids.end(), d.frames[size_t(i)].id) != ids.end() ? s.test : s.train).push_back(i);
  if (s.test.empty() || s.train.empty()) {
    log::warn(where, ": the loaded window holds ", s.test.size(), " of the sequence's test frames and ",
              s.train.size(), " others; the protocol split stays");
    return;
  }
  d.split = std::move(s);
}

}  // namespace

Dataset load_kitti360(const std::string& root_s, const LoadOptions& opt, bool synthetic) {
  const fs::path root(root_s);
  Json meta = Json::object();
  Sensor sensor = sensor_preset("kitti360");
  std::string freq_default = "standard", seq_default;
  int start_default = 1538, stride_meta = -1, count_meta = -1;
  if (synthetic) {
    const std::string where = (root / "sgnlf_dataset.json").string();
    meta = load_json_file(where);
    if (!meta.is_object()) throw IoError(where + ": expected a JSON object");
    if (!meta.contains("sequence") || !meta.contains("frequency") || !meta.contains("first_frame") ||
        !meta.contains("stride") || !meta.contains("frames"))
      throw IoError(where + ": missing one of sequence, frequency, first_frame, stride, frames");
    seq_default = meta_string(meta, "sequence", where);
    freq_default = meta_string(meta, "frequency", where);
    if (freq_default != "standard" && freq_default != "low")
      throw IoError(where + ": frequency '" + freq_default + "' (expected standard or low)");
    // A stride of 0 loaded one frame many times (or hung the loader on a missing id), a
    // negative one walked backwards forever.
    start_default = meta_int(meta, "first_frame", 0, where);
    stride_meta = meta_int(meta, "stride", 1, where);
    count_meta = meta_int(meta, "frames", 1, where);
    if (meta.contains("name")) (void)meta_string(meta, "name", where);
    const std::string sj = (root / "sensor.json").string();
    if (!fs::exists(sj)) throw IoError(sj + ": missing sensor description");
    sensor = sensor_from_json(load_json_file(sj), sj);
  }
  sensor = resolve_sensor(opt, sensor);
  const std::string drive = pick_drive(root, opt.sequence.empty() ? seq_default : opt.sequence);
  const std::string freq = resolve_frequency(opt, freq_default);
  int stride = default_stride(opt, freq, sensor.rate_hz);
  int count = default_count(opt, freq);
  if (synthetic && opt.stride < 0 && opt.rate_hz <= 0.0 && freq == freq_default) stride = stride_meta;
  if (synthetic && opt.frames < 0 && freq == freq_default) count = count_meta;
  const int start = opt.start >= 0 ? opt.start : start_default;

  // protocol §2: LiDAR→world = imu_to_world · cam00_to_imu · inverse(cam00_to_velo).
  const std::string c2p = (root / "calibration" / "calib_cam_to_pose.txt").string();
  const std::string c2v = (root / "calibration" / "calib_cam_to_velo.txt").string();
  for (const auto& f : {c2p, c2v})
    if (!fs::exists(f)) throw IoError(f + ": missing calibration file");
  const Pose T_imu_cam = io::key_pose(io::read_key_values(c2p), "image_00", c2p);
  const Pose T_velo_cam = io::key_pose(io::read_key_values(c2v), "", c2v);
  const Pose T_imu_lidar = T_imu_cam * T_velo_cam.inverse();

  const std::string pose_file = (root / "data_poses" / drive / "poses.txt").string();
  if (!fs::exists(pose_file)) throw IoError(pose_file + ": missing pose file");
  const auto poses = io::read_indexed_poses(pose_file);
  const fs::path scan_dir = root / "data_3d_raw" / drive / "velodyne_points" / "data";
  const auto scans = scan_ids(scan_dir, ".bin");
  std::vector<int> avail;
  for (const auto& [id, T] : poses)
    if (std::binary_search(scans.begin(), scans.end(), id)) avail.push_back(id);
  if (avail.size() < poses.size())
    log::warn(pose_file, ": ", poses.size() - avail.size(), " posed frames have no scan file in ",
              scan_dir.string());
  const auto ids = select_window(avail, start, stride, count, pose_file);
  const auto stamps = read_kitti360_timestamps(scan_dir.parent_path() / "timestamps.txt");

  Dataset d;
  d.name = synthetic ? meta.value("name", drive) : drive + "@" + std::to_string(start);
  d.source = synthetic ? "synthetic" : "kitti360";
  if (synthetic) d.planar_reference = meta_planar_reference(meta, (root / "sgnlf_dataset.json").string());
  d.path = root_s;
  d.frequency = freq;
  d.sensor = sensor;
  ProjectionStats dropped;
  // Moving actors' ground truth (synthetic sequences with actors, actor_truth.hpp).
  const bool actors = synthetic && fs::exists(actor_truth_path(root_s));
  const auto boxes = actors ? read_actor_boxes(actor_truth_path(root_s)) : std::map<int, std::vector<ActorBox>>{};
  for (int id : ids) {
    Frame f;
    f.id = id;
    f.timestamp_s = stamps.count(id) ? stamps.at(id) : id / sensor.rate_hz;
    f.T_world_lidar = poses.at(id) * T_imu_lidar;
    load_frame_scan(f, frame_file(scan_dir, id, 10, ".bin"), sensor, opt.load_points, dropped,
                    actors ? actor_labels_path(root_s, id) : "");
    if (actors) {
      if (!boxes.count(id)) throw IoError(actor_truth_path(root_s) + ": no entry for frame " + std::to_string(id));
      f.actors = boxes.at(id);
    }
    d.frames.push_back(std::move(f));
  }
  finish_dataset(d, dropped);
  if (synthetic && meta.contains("test_frame_ids")) apply_test_frame_ids(d, meta, (root / "sgnlf_dataset.json").string());
  return d;
}

Dataset load_kitti_odometry(const std::string& root_s, const LoadOptions& opt) {
  const fs::path root(root_s);
  std::string seq = opt.sequence;
  if (seq.empty()) {
    std::vector<std::string> seqs;
    for (const auto& e : fs::directory_iterator(root / "sequences")) seqs.push_back(e.path().filename().string());
    std::sort(seqs.begin(), seqs.end());
    if (seqs.empty()) throw IoError((root / "sequences").string() + ": no sequence folder");
    seq = seqs.front();
  }
  const Sensor sensor = resolve_sensor(opt, sensor_preset("kitti360"));  // HDL-64E
  const std::string freq = resolve_frequency(opt, "standard");
  const fs::path sdir = root / "sequences" / seq;
  const std::string calib = (sdir / "calib.txt").string();
  if (!fs::exists(calib)) throw IoError(calib + ": missing calibration file");
  const Pose Tr = io::key_pose(io::read_key_values(calib), "Tr", calib);  // velodyne → camera 0
  const std::string pose_file = (root / "poses" / (seq + ".txt")).string();
  if (!fs::exists(pose_file)) throw IoError(pose_file + ": missing pose file");
  const auto cam_poses = io::read_kitti_poses(pose_file);
  const auto scans = scan_ids(sdir / "velodyne", ".bin");
  if (!scans.empty() && size_t(scans.back()) >= cam_poses.size())
    throw IoError(pose_file + ": " + std::to_string(cam_poses.size()) + " pose rows, but scan " +
                  std::to_string(scans.back()) + " exists (one row per frame expected)");
  std::vector<double> times;
  if (fs::exists(sdir / "times.txt")) {
    std::ifstream f(sdir / "times.txt");
    std::string l;
    for (int k = 1; std::getline(f, l); ++k) {
      const auto v = io::parse_numbers(l, (sdir / "times.txt").string(), k);
      if (v.size() == 1) times.push_back(v[0]);
    }
  }
  const int start = opt.start >= 0 ? opt.start : (scans.empty() ? 0 : scans.front());
  const auto ids = select_window(scans, start, default_stride(opt, freq, sensor.rate_hz),
                                 default_count(opt, freq), (sdir / "velodyne").string());
  Dataset d;
  d.name = "kitti-odometry-" + seq + "@" + std::to_string(ids.front());
  d.source = "kitti-odometry";
  d.path = root_s;
  d.frequency = freq;
  d.sensor = sensor;
  ProjectionStats dropped;
  const Pose Tr_inv = Tr.inverse();
  for (int id : ids) {
    Frame f;
    f.id = id;
    f.timestamp_s = size_t(id) < times.size() ? times[size_t(id)] : id / sensor.rate_hz;
    f.T_world_lidar = Tr_inv * cam_poses[size_t(id)] * Tr;  // inv(Tr) · P_cam0(k) · Tr
    load_frame_scan(f, frame_file(sdir / "velodyne", id, 6, ".bin"), sensor, opt.load_points, dropped);
    d.frames.push_back(std::move(f));
  }
  finish_dataset(d, dropped);
  return d;
}

}  // namespace sgnlf::detail
