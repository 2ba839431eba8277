#include "io/trajectory_io.hpp"

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/config.hpp"
#include "core/error.hpp"

namespace sgnlf::io {
namespace {

std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw IoError(path + ": cannot open file");
  std::vector<std::string> lines;
  std::string l;
  while (std::getline(f, l)) {
    if (!l.empty() && l.back() == '\r') l.pop_back();
    lines.push_back(l);
  }
  return lines;
}

bool blank(const std::string& s) { return s.find_first_not_of(" \t") == std::string::npos; }

std::string fmt(double v) {
  char b[40];
  std::snprintf(b, sizeof(b), "%.17g", v);
  return b;
}

// |RᵀR − I| (Frobenius) below 1e-3 and det R > 0: a rotation, not a reflection or a scaling.
// Real KITTI / KITTI-360 calibrations and poses are orthonormal to ~1e-6.
std::string rigidity_problem(const Pose& T) {
  const Mat3 R = T.linear();
  const double err = (R.transpose() * R - Mat3::Identity()).norm();
  if (!(err < 1e-3)) return "not a rigid pose (|RᵀR − I| = " + std::to_string(err) + ")";
  if (!(R.determinant() > 0)) return "a reflection, not a rotation (det R = " + std::to_string(R.determinant()) + ")";
  if (!T.translation().allFinite()) return "non-finite translation";
  return "";
}

void check_pose(const Pose& T, const std::string& path, int line) {
  const std::string p = rigidity_problem(T);
  if (!p.empty()) throw IoError(path + ":" + std::to_string(line) + ": " + p);
}

}  // namespace

std::vector<double> parse_numbers(const std::string& text, const std::string& path, int line) {
  std::vector<double> v;
  std::istringstream s(text);
  std::string tok;
  while (s >> tok) {
    errno = 0;
    char* end = nullptr;
    const double x = std::strtod(tok.c_str(), &end);
    if (end != tok.c_str() + tok.size() || errno == ERANGE || !std::isfinite(x))
      throw IoError(path + ":" + std::to_string(line) + ": field " + std::to_string(v.size() + 1) +
                    " '" + tok + "' is not a finite number");
    v.push_back(x);
  }
  return v;
}

std::vector<Pose> read_kitti_poses(const std::string& path) {
  const auto lines = read_lines(path);
  std::vector<Pose> out;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (blank(lines[i])) continue;
    const auto v = parse_numbers(lines[i], path, int(i + 1));
    if (v.size() != 12)
      throw IoError(path + ":" + std::to_string(i + 1) + ": expected 12 numbers, found " +
                    std::to_string(v.size()));
    out.push_back(pose_from_3x4(v.data()));
    check_pose(out.back(), path, int(i + 1));
  }
  if (out.empty()) throw IoError(path + ": no poses in file");
  return out;
}

void write_kitti_poses(const std::string& path, const std::vector<Pose>& poses) {
  std::string s;
  for (const auto& T : poses) {
    double v[12];
    pose_to_3x4(T, v);
    for (int k = 0; k < 12; ++k) s += fmt(v[k]) + (k == 11 ? "\n" : " ");
  }
  write_text_file(path, s);
}

std::map<int, Pose> read_indexed_poses(const std::string& path) {
  const auto lines = read_lines(path);
  std::map<int, Pose> out;
  int last = -1;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (blank(lines[i])) continue;
    const int ln = int(i + 1);
    const auto v = parse_numbers(lines[i], path, ln);
    if (v.size() != 13)
      throw IoError(path + ":" + std::to_string(ln) + ": expected frame id + 12 numbers, found " +
                    std::to_string(v.size()) + " fields");
    if (v[0] != std::floor(v[0]) || v[0] < 0 || v[0] > double(INT_MAX) || int(v[0]) <= last)
      throw IoError(path + ":" + std::to_string(ln) + ": frame id " + fmt(v[0]) +
                    " is not an integer greater than the previous id " + std::to_string(last));
    last = int(v[0]);
    out[last] = pose_from_3x4(v.data() + 1);
    check_pose(out[last], path, ln);
  }
  if (out.empty()) throw IoError(path + ": no poses in file");
  return out;
}

void write_indexed_poses(const std::string& path, const std::vector<int>& ids,
                         const std::vector<Pose>& poses) {
  std::string s;
  for (size_t i = 0; i < ids.size(); ++i) {
    double v[12];
    pose_to_3x4(poses.at(i), v);
    s += std::to_string(ids[i]);
    for (int k = 0; k < 12; ++k) s += " " + fmt(v[k]);
    s += "\n";
  }
  write_text_file(path, s);
}

void write_tum_poses(const std::string& path, const std::vector<double>& timestamps,
                     const std::vector<Pose>& poses) {
  std::string s = "# timestamp tx ty tz qx qy qz qw\n";
  for (size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Quaterniond q(poses[i].linear());
    const Vec3 t = poses[i].translation();
    s += fmt(timestamps.at(i)) + " " + fmt(t.x()) + " " + fmt(t.y()) + " " + fmt(t.z()) + " " +
         fmt(q.x()) + " " + fmt(q.y()) + " " + fmt(q.z()) + " " + fmt(q.w()) + "\n";
  }
  write_text_file(path, s);
}

std::vector<std::pair<double, Pose>> read_tum_poses(const std::string& path) {
  const auto lines = read_lines(path);
  std::vector<std::pair<double, Pose>> out;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (blank(lines[i]) || lines[i].find('#') != std::string::npos) continue;
    const auto v = parse_numbers(lines[i], path, int(i + 1));
    if (v.size() != 8)
      throw IoError(path + ":" + std::to_string(i + 1) + ": expected 8 fields, found " +
                    std::to_string(v.size()));
    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (std::abs(q.norm() - 1.0) > 1e-3)
      throw IoError(path + ":" + std::to_string(i + 1) + ": quaternion is not unit");
    Pose T = Pose::Identity();
    T.linear() = q.normalized().toRotationMatrix();
    T.translation() = Vec3(v[1], v[2], v[3]);
    out.emplace_back(v[0], T);
  }
  return out;
}

std::map<std::string, std::vector<double>> read_key_values(const std::string& path) {
  const auto lines = read_lines(path);
  std::map<std::string, std::vector<double>> kv;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (blank(lines[i])) continue;
    const auto colon = lines[i].find(':');
    const std::string key = colon == std::string::npos ? "" : lines[i].substr(0, colon);
    const std::string rest = colon == std::string::npos ? lines[i] : lines[i].substr(colon + 1);
    kv[key] = parse_numbers(rest, path, int(i + 1));
  }
  return kv;
}

Pose key_pose(const std::map<std::string, std::vector<double>>& kv, const std::string& key,
              const std::string& path) {
  const auto it = kv.find(key);
  if (it == kv.end())
    throw IoError(path + ": missing calibration entry '" + (key.empty() ? "<3x4 matrix>" : key) + "'");
  if (it->second.size() != 12)
    throw IoError(path + ": calibration entry '" + key + "' has " +
                  std::to_string(it->second.size()) + " numbers, expected 12");
  const Pose T = pose_from_3x4(it->second.data());
  // A calibration that is not rigid (a typo, a projection matrix under the wrong key, a scale)
  // would silently shear every scan.
  const std::string p = rigidity_problem(T);
  if (!p.empty())
    throw IoError(path + ": calibration entry '" + (key.empty() ? "<3x4 matrix>" : key) + "' is " + p);
  return T;
}

}  // namespace sgnlf::io
