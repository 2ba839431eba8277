// nuScenes (v1.0-mini layout) loader: LIDAR_TOP sample_data from the JSON tables, LiDAR→world =
// ego_to_world · lidar_to_ego (protocol §2), frames sorted by timestamp inside one scene.
// Low frequency uses the 2 Hz keyframes, standard the 20 Hz sweeps. Also the scan-folder loader.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "core/config.hpp"
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

// Typed field access: a field of the wrong JSON type names the table file, the record and the
// key (nlohmann's type_error named none of them).
std::string where_rec(const std::string& file, const Json& rec) {
  const auto it = rec.find("token");
  return file + ": record " + (it != rec.end() && it->is_string() ? "'" + it->get<std::string>() + "'" : "?");
}

const Json& field(const std::string& file, const Json& rec, const std::string& key) {
  const auto it = rec.find(key);
  if (it == rec.end()) throw IoError(where_rec(file, rec) + " lacks '" + key + "'");
  return *it;
}

std::string str_field(const std::string& file, const Json& rec, const std::string& key) {
  const Json& v = field(file, rec, key);
  if (!v.is_string())
    throw IoError(where_rec(file, rec) + ": '" + key + "' must be a string, found " + v.dump());
  return v.get<std::string>();
}

// Optional string with a fallback (sensor channel, scene name, file name).
std::string str_field_or(const std::string& file, const Json& rec, const std::string& key,
                         const std::string& fallback) {
  return rec.contains(key) ? str_field(file, rec, key) : fallback;
}

double num_field(const std::string& file, const Json& v, const Json& rec, const std::string& key) {
  if (!v.is_number())
    throw IoError(where_rec(file, rec) + ": '" + key + "' must hold numbers, found " + v.dump());
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw IoError(where_rec(file, rec) + ": '" + key + "' is not finite");
  return x;
}

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
    if (!j[i]["token"].is_string())
      throw IoError(t.file + ": record " + std::to_string(i) + ": 'token' must be a string, found " +
                    j[i]["token"].dump());
    t.by_token[j[i]["token"].get<std::string>()] = j[i];
  }
  return t;
}

// `rec` comes from `from` (a file name, for errors); its `key` names a record of `t`.
const Json& lookup(const Table& t, const std::string& from, const Json& rec, const std::string& key) {
  const std::string tok = str_field(from, rec, key);
  const auto it = t.by_token.find(tok);
  if (it == t.by_token.end())
    throw IoError(t.file + ": no record with token '" + tok + "' (from " + key + " in " + from + ")");
  return it->second;
}

Pose pose_of(const Json& rec, const std::string& where) {
  const Json& tj = field(where, rec, "translation");
  const Json& qj = field(where, rec, "rotation");
  if (!tj.is_array() || !qj.is_array() || tj.size() != 3 || qj.size() != 4)
    throw IoError(where_rec(where, rec) + " lacks translation[3] / rotation[4]");
  double q[4], t[3];
  for (int k = 0; k < 4; ++k) q[k] = num_field(where, qj[size_t(k)], rec, "rotation");
  for (int k = 0; k < 3; ++k) t[k] = num_field(where, tj[size_t(k)], rec, "translation");
  // w, x, y, z. nuScenes stores unit quaternions; a zero (or far from unit) one is a broken
  // record, which Eigen's normalized() would have turned into the identity without a word.
  const Eigen::Quaterniond quat(q[0], q[1], q[2], q[3]);
  if (!(std::abs(quat.norm() - 1.0) < 1e-3))
    throw IoError(where_rec(where, rec) + ": rotation quaternion has norm " +
                  std::to_string(quat.norm()) + " (a unit quaternion w, x, y, z expected)");
  Pose T = Pose::Identity();
  T.linear() = quat.normalized().toRotationMatrix();
  T.translation() = Vec3(t[0], t[1], t[2]);
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
    const Json& c = lookup(cal, sd.file, r, "calibrated_sensor_token");
    const std::string fname = str_field_or(sd.file, r, "filename", "");
    const bool lidar =
        sensor_t.by_token.empty()
            ? fname.find("LIDAR_TOP") != std::string::npos
            : str_field_or(sensor_t.file, lookup(sensor_t, cal.file, c, "sensor_token"), "channel", "") == "LIDAR_TOP";
    if (!lidar) continue;
    const std::string sc = str_field_or(
        scene.file, lookup(scene, sample.file, lookup(sample, sd.file, r, "sample_token"), "scene_token"), "name", "?");
    int64_t ts = 0;
    if (r.contains("timestamp")) {
      if (!r["timestamp"].is_number_integer())
        throw IoError(where_rec(sd.file, r) + ": 'timestamp' must be an integer (microseconds), found " +
                      r["timestamp"].dump());
      ts = r["timestamp"].get<int64_t>();
    }
    bool key = false;
    if (r.contains("is_key_frame")) {
      if (!r["is_key_frame"].is_boolean())
        throw IoError(where_rec(sd.file, r) + ": 'is_key_frame' must be true or false, found " +
                      r["is_key_frame"].dump());
      key = r["is_key_frame"].get<bool>();
    }
    per_scene[sc].push_back({ts, key, &r, sc});
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
  // Keyframes are already 2 Hz, sweeps the sensor's 20 Hz; a wanted rate takes every k-th.
  const double native_hz = freq == "low" ? 2.0 : sensor.rate_hz;
  const int stride = opt.stride > 0     ? opt.stride
                     : opt.rate_hz > 0.0 ? std::max(1, int(std::lround(native_hz / opt.rate_hz)))
                                         : 1;
  const auto ids = select_window(avail, std::max(0, opt.start), stride, default_count(opt, freq), sd.file);
  Dataset d;
  d.name = sc;
  d.source = "nuscenes";
  d.planar_reference = true;  // ego poses with z = 0 (dataset.hpp)
  d.path = root_s;
  d.frequency = freq;
  d.sensor = sensor;
  ProjectionStats dropped;
  for (int id : ids) {
    const Json& r = *recs[size_t(id)].j;
    Frame f;
    f.id = id;
    f.timestamp_s = recs[size_t(id)].ts * 1e-6;
    f.T_world_lidar = pose_of(lookup(ego, sd.file, r, "ego_pose_token"), ego.file) *
                      pose_of(lookup(cal, sd.file, r, "calibrated_sensor_token"), cal.file);
    load_frame_scan(f, (root / str_field(sd.file, r, "filename")).string(), sensor, opt.load_points, dropped);
    d.frames.push_back(std::move(f));
  }
  finish_dataset(d, dropped);
  return d;
}

}  // namespace sgnlf::detail
