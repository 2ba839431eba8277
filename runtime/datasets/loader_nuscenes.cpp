// nuScenes (v1.0-mini layout) loader: LIDAR_TOP sample_data from the JSON tables, LiDAR→world =
// ego_to_world · lidar_to_ego (protocol §2), frames sorted by timestamp inside one scene.
// Low frequency uses the 2 Hz keyframes, standard the 20 Hz sweeps. Also the scan-folder loader.
#include <algorithm>
#include <filesystem>
#include <map>

#include "core/error.hpp"
#include "core/log.hpp"
#include "datasets/loader_internal.hpp"
#include "io/scan_io.hpp"

namespace sgnlf::detail {
namespace fs = std::filesystem;

namespace {

struct Table {
  std::string file;
  std::map<std::string, Json> by_token;
};

Table load_table(const fs::path& dir, const std::string& name, bool required = true) {
  Table t;
  t.file = (dir / (name + ".json")).string();
  if (!fs::exists(t.file)) {
    if (required) throw IoError(t.file + ": missing nuScenes table '" + name + "'");
    return t;
  }
  const Json j = load_json_file(t.file);
  if (!j.is_array()) throw IoError(t.file + ": expected a JSON array of records");
  for (size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_object() || !j[i].contains("token"))
      throw IoError(t.file + ": record " + std::to_string(i) + " has no 'token'");
    t.by_token[j[i]["token"].get<std::string>()] = j[i];
  }
  return t;
}

const Json& lookup(const Table& t, const Json& rec, const std::string& key) {
  if (!rec.contains(key)) throw IoError(t.file + ": referencing record lacks '" + key + "'");
  const auto it = t.by_token.find(rec[key].get<std::string>());
  if (it == t.by_token.end())
    throw IoError(t.file + ": no record with token '" + rec[key].get<std::string>() + "' (from " + key + ")");
  return it->second;
}

Pose pose_of(const Json& rec, const std::string& where) {
  if (!rec.contains("translation") || !rec.contains("rotation") || rec["translation"].size() != 3 ||
      rec["rotation"].size() != 4)
    throw IoError(where + ": record " + rec.value("token", "?") + " lacks translation[3] / rotation[4]");
  const auto& q = rec["rotation"];  // w, x, y, z
  Pose T = Pose::Identity();
  T.linear() = Eigen::Quaterniond(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(),
                                  q[3].get<double>()).normalized().toRotationMatrix();
  const auto& t = rec["translation"];
  T.translation() = Vec3(t[0].get<double>(), t[1].get<double>(), t[2].get<double>());
  return T;
}

}  // namespace

Dataset load_nuscenes(const std::string& root_s, const LoadOptions& opt) {
  const fs::path root(root_s);
  fs::path tdir;
  for (const char* v : {"v1.0-mini", "v1.0-trainval", "v1.0-test"})
    if (fs::is_directory(root / v)) { tdir = root / v; break; }
  if (tdir.empty()) throw IoError(root_s + ": missing table folder v1.0-mini/ (nuScenes JSON tables)");
  const Table sd = load_table(tdir, "sample_data"), ego = load_table(tdir, "ego_pose"),
              cal = load_table(tdir, "calibrated_sensor"), sample = load_table(tdir, "sample"),
              scene = load_table(tdir, "scene"), sensor_t = load_table(tdir, "sensor", false);
  struct Rec { int64_t ts; bool key; const Json* j; std::string scene; };
  std::map<std::string, std::vector<Rec>> per_scene;
  for (const auto& [tok, r] : sd.by_token) {
    const Json& c = lookup(cal, r, "calibrated_sensor_token");
    const std::string fname = r.value("filename", "");
    const bool lidar = sensor_t.by_token.empty()
                           ? fname.find("LIDAR_TOP") != std::string::npos
                           : lookup(sensor_t, c, "sensor_token").value("channel", "") == "LIDAR_TOP";
    if (!lidar) continue;
    const std::string sc = lookup(scene, lookup(sample, r, "sample_token"), "scene_token").value("name", "?");
    per_scene[sc].push_back({r.value("timestamp", int64_t(0)), r.value("is_key_frame", false), &r, sc});
  }
  if (per_scene.empty()) throw IoError(sd.file + ": no LIDAR_TOP sample_data records");
  const std::string sc = opt.sequence.empty() ? per_scene.begin()->first : opt.sequence;
  if (!per_scene.count(sc)) throw IoError(scene.file + ": no scene named '" + sc + "' with LIDAR_TOP data");
  const std::string freq = resolve_frequency(opt, "low");
  // One scene only: a window never crosses a scene boundary (protocol §2).
  std::vector<Rec> recs;
  for (const auto& r : per_scene[sc])
    if (freq == "standard" || r.key) recs.push_back(r);
  std::sort(recs.begin(), recs.end(), [](const Rec& a, const Rec& b) { return a.ts < b.ts; });
  std::vector<int> avail(recs.size());
  for (size_t i = 0; i < recs.size(); ++i) avail[i] = int(i);
  const Sensor sensor = resolve_sensor(opt, sensor_preset("nuscenes"));
  const int stride = opt.stride > 0 ? opt.stride : 1;  // keyframes are already 2 Hz
  const auto ids = select_window(avail, std::max(0, opt.start), stride, default_count(opt, freq), sd.file);
  Dataset d;
  d.name = sc;
  d.source = "nuscenes";
  d.path = root_s;
  d.frequency = freq;
  d.sensor = sensor;
  ProjectionStats dropped;
  for (int id : ids) {
    const Json& r = *recs[size_t(id)].j;
    Frame f;
    f.id = id;
    f.timestamp_s = recs[size_t(id)].ts * 1e-6;
    f.T_world_lidar = pose_of(lookup(ego, r, "ego_pose_token"), ego.file) *
                      pose_of(lookup(cal, r, "calibrated_sensor_token"), cal.file);
    load_frame_scan(f, (root / r.value("filename", "")).string(), sensor, opt.load_points, dropped);
    d.frames.push_back(std::move(f));
  }
  finish_dataset(d, dropped);
  return d;
}

Dataset load_scans(const std::string& path, const LoadOptions& opt) {
  std::vector<std::string> files;
  if (fs::is_regular_file(path)) {
    files.push_back(path);
  } else {
    for (const auto& e : fs::directory_iterator(path))
      if (e.is_regular_file() && io::is_scan_file(e.path().string())) files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
  }
  const bool nus = files.front().size() > 8 && files.front().rfind(".pcd.bin") == files.front().size() - 8;
  const Sensor sensor = resolve_sensor(opt, sensor_preset(nus ? "nuscenes" : "kitti360"));
  Dataset d;
  d.name = fs::path(path).filename().string();
  d.source = "scans";
  d.path = path;
  d.frequency = resolve_frequency(opt, "standard");
  d.sensor = sensor;
  ProjectionStats dropped;
  const size_t first = size_t(std::max(0, opt.start));
  const size_t stride = size_t(opt.stride > 0 ? opt.stride : 1);
  for (size_t i = first; i < files.size() && (opt.frames < 0 || int(d.frames.size()) < opt.frames); i += stride) {
    Frame f;
    f.id = int(i);
    f.timestamp_s = double(i) / sensor.rate_hz;  // no pose and no clock: identity poses
    load_frame_scan(f, files[i], sensor, opt.load_points, dropped);
    d.frames.push_back(std::move(f));
  }
  log::warn(path, ": plain scans carry no poses; ground-truth poses are the identity");
  finish_dataset(d, dropped);
  return d;
}

}  // namespace sgnlf::detail
