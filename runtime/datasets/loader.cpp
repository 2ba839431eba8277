#include "datasets/loader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/config.hpp"
#include "core/config_fields.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "datasets/actor_truth.hpp"
#include "datasets/load_args.hpp"
#include "datasets/loader_internal.hpp"
#include "datasets/protocol.hpp"
#include "io/scan_io.hpp"

namespace sgnlf {
namespace fs = std::filesystem;

void LoadOptions::validate() const {
  if (!frequency.empty() && frequency != "standard" && frequency != "low")
    throw ConfigError("load options: frequency '" + frequency + "' (expected standard or low)");
  if (frames == 0 || frames < -1) throw ConfigError("load options: frames = " + std::to_string(frames));
  if (stride == 0 || stride < -1) throw ConfigError("load options: stride = " + std::to_string(stride));
  if (start < -1) throw ConfigError("load options: start = " + std::to_string(start));
  if (!std::isfinite(rate_hz) || rate_hz < 0.0 || rate_hz > 1e4)
    throw ConfigError("load options: rate_hz = " + std::to_string(rate_hz) + " (a scan rate in Hz, 0 < rate <= 10000; 0 = the data's)");
  for (size_t k = 0; k < test_frames.size(); ++k) {
    if (test_frames[k] < 0)
      throw ConfigError("load options: test_frames[" + std::to_string(k) +
                        "] = " + std::to_string(test_frames[k]) + " (positions in the window are >= 0)");
    for (size_t q = 0; q < k; ++q)
      if (test_frames[q] == test_frames[k])
        throw ConfigError("load options: test_frames lists position " +
                          std::to_string(test_frames[k]) + " twice");
  }
}

bool LoadOptions::is_default() const { return to_json().empty(); }

Json LoadOptions::to_json() const { return config::write_fields(*this); }

LoadOptions LoadOptions::from_json(const Json& j, const std::string& where) {
  LoadOptions o;
  ConfigReader r(j, where);
  config::read_fields_here(r, o);
  r.finish();
  try {
    o.validate();
  } catch (const ConfigError& e) {
    throw ConfigError(where + ": " + e.what());
  }
  return o;
}

bool operator==(const LoadOptions& a, const LoadOptions& b) { return a.to_json() == b.to_json(); }

namespace {
// The split of `opt.test_frames` over the loaded window, replacing the protocol's.
void apply_test_frames(Dataset& d, const LoadOptions& opt) {
  if (opt.test_frames.empty()) return;
  const int n = int(d.frames.size());
  Split s;
  for (int p : opt.test_frames)
    if (p >= n)
      throw ConfigError(d.path + ": test frame position " + std::to_string(p) + " but the window holds " +
                        std::to_string(n) + " frames (positions 0.." + std::to_string(n - 1) + ")");
  for (int f = 0; f < n; ++f) {
    const bool test = std::find(opt.test_frames.begin(), opt.test_frames.end(), f) != opt.test_frames.end();
    (test ? s.test : s.train).push_back(f);
  }
  if (s.train.empty())
    throw ConfigError(d.path + ": test_frames leave no training frame among the " + std::to_string(n));
  d.split = std::move(s);
  log::info(d.path, ": test frames (positions) replaced by the load options: ", d.split.test.size(),
            " test, ", d.split.train.size(), " train");
}
}  // namespace

std::string detect_layout(const std::string& path) {
  const fs::path p(path);
  if (!fs::exists(p)) throw IoError(path + ": no such file or directory");
  if (fs::is_regular_file(p)) {
    if (io::is_scan_file(path)) return "scans";
    throw IoError(path + ": not a scan file (.bin / .pcd.bin) nor a dataset folder");
  }
  if (fs::exists(p / "sgnlf_dataset.json")) return "synthetic";
  if (fs::exists(p / "data_3d_raw") || fs::exists(p / "data_poses")) return "kitti360";
  if (fs::exists(p / "sequences") && fs::exists(p / "poses")) return "kitti-odometry";
  if (fs::exists(p / "samples") || fs::exists(p / "v1.0-mini") || fs::exists(p / "sweeps"))
    return "nuscenes";
  for (const auto& e : fs::directory_iterator(p))
    if (e.is_regular_file() && io::is_scan_file(e.path().string())) return "scans";
  throw IoError(path + ": unknown dataset layout (expected sgnlf_dataset.json, data_3d_raw/, "
                       "sequences/ + poses/, samples/ + v1.0-mini/, or .bin scans)");
}

Dataset load_dataset(const std::string& path, const LoadOptions& opt) {
  opt.validate();
  const std::string layout = detect_layout(path);
  log::info("loading ", path, " (layout ", layout, ")");
  Dataset d = layout == "synthetic"        ? detail::load_kitti360(path, opt, true)
              : layout == "kitti360"       ? detail::load_kitti360(path, opt, false)
              : layout == "kitti-odometry" ? detail::load_kitti_odometry(path, opt)
              : layout == "nuscenes"       ? detail::load_nuscenes(path, opt)
                                           : detail::load_scans(path, opt);
  apply_test_frames(d, opt);
  return d;
}

namespace detail {

std::vector<int> select_window(const std::vector<int>& available, int start, int stride, int count,
                               const std::string& where) {
  if (available.empty()) throw IoError(where + ": no frames");
  // Every caller resolves the defaults first; a stride below 1 would repeat one frame or never end.
  if (stride < 1 || count < 1)
    throw ConfigError(where + ": window stride " + std::to_string(stride) + " and count " +
                      std::to_string(count) + " (both must be >= 1)");
  // Walks the available ids, not the grid: a far-away start (or a file named 2147483647.bin)
  // must not cost billions of look-ups. `missing` counts grid ids without a frame, as before.
  std::vector<int> ids;
  for (int a : available) {
    if (int(ids.size()) >= count) break;
    if (!ids.empty() && a == ids.back()) continue;  // "7.bin" and "07.bin": one frame id
    if (a >= start && (static_cast<long long>(a) - start) % stride == 0) ids.push_back(a);
  }
  const long long last = int(ids.size()) >= count ? ids.back() : available.back();
  const long long grid = last >= start ? (last - start) / stride + 1 : 0;
  const long long missing = grid - static_cast<long long>(ids.size());
  if (missing > 0)
    log::warn(where, ": skipped ", missing, " frame ids without a pose or scan in the window from ",
              start, " with stride ", stride);
  if (ids.empty())
    throw IoError(where + ": no frame in the window starting at " + std::to_string(start) +
                  " (frames " + std::to_string(available.front()) + ".." +
                  std::to_string(available.back()) + ")");
  if (int(ids.size()) < count)
    log::warn(where, ": only ", ids.size(), " of ", count, " requested frames available");
  return ids;
}

std::string resolve_frequency(const LoadOptions& opt, const std::string& fallback) {
  if (!opt.frequency.empty()) return opt.frequency;
  if (opt.rate_hz > 0.0) return frequency_class(opt.rate_hz);
  return fallback;
}

int default_stride(const LoadOptions& opt, const std::string& frequency, double rate_hz) {
  if (opt.stride > 0) return opt.stride;
  if (opt.rate_hz > 0.0) return std::max(1, int(std::lround(rate_hz / opt.rate_hz)));
  if (frequency == "low") return std::max(1, int(std::lround(rate_hz / 2.0)));  // 2 Hz
  return 1;
}

int default_count(const LoadOptions& opt, const std::string& frequency) {
  if (opt.frames > 0) return opt.frames;
  return frequency == "low" ? 36 : 64;
}

Sensor resolve_sensor(const LoadOptions& opt, const Sensor& layout_default) {
  if (opt.sensor.empty()) return layout_default;
  if (fs::is_regular_file(opt.sensor)) return sensor_from_json(load_json_file(opt.sensor), opt.sensor);
  return sensor_preset(opt.sensor);
}

void load_frame_scan(Frame& f, const std::string& scan_path, const Sensor& s, bool load_points,
                     ProjectionStats& dropped, const std::string& labels_path,
                     float intensity_scale) {
  io::ScanReadStats rs;
  auto pts = io::read_scan(scan_path, &rs);
  if (intensity_scale != 1.0f)
    for (auto& p : pts) p.intensity *= intensity_scale;
  std::vector<uint16_t> labels;
  if (!labels_path.empty()) {
    labels = read_labels(labels_path);
    if (labels.size() != rs.records || rs.non_finite > 0)
      throw IoError(labels_path + ": " + std::to_string(labels.size()) + " labels for the " +
                    std::to_string(rs.records) + " records of " + scan_path +
                    (rs.non_finite > 0 ? " (some of them NaN/Inf)" : ""));
  }
  ProjectionStats ps;
  f.image = project_points(s, pts, &ps);
  log::debug(scan_path, ": ", rs.records, " points; not projected: ", rs.non_finite, " NaN/Inf, ",
             ps.beyond_range, " at >= ", s.max_range_m, " m, ", ps.below_min_range, " within ",
             s.min_range_m, " m, ", ps.out_of_fov, " outside the field of view; ", ps.occluded,
             " behind a nearer return in their pixel");
  dropped.non_finite += rs.non_finite;
  dropped.beyond_range += ps.beyond_range;
  dropped.below_min_range += ps.below_min_range;
  dropped.out_of_fov += ps.out_of_fov;
  dropped.occluded += ps.occluded;
  dropped.projected += ps.projected;
  if (!load_points) return;
  auto kept = [&](const PointXYZI& p) {
    return s.in_range(std::sqrt(double(p.x) * p.x + double(p.y) * p.y + double(p.z) * p.z));
  };
  if (!labels.empty()) {  // the labels stay with their points
    size_t n = 0;
    for (size_t i = 0; i < pts.size(); ++i)
      if (kept(pts[i])) labels[n++] = labels[i];
    labels.resize(n);
    f.labels = std::move(labels);
  }
  pts.erase(std::remove_if(pts.begin(), pts.end(), [&](const PointXYZI& p) { return !kept(p); }), pts.end());
  f.points = std::move(pts);
}

void finish_dataset(Dataset& d, const ProjectionStats& dropped) {
  if (d.frames.empty()) throw IoError(d.path + ": no frames loaded");
  const double t0 = d.frames.front().timestamp_s;
  for (auto& f : d.frames) f.timestamp_s -= t0;
  d.split = protocol_split(int(d.frames.size()), d.frequency);
  size_t pts = 0;
  for (const auto& f : d.frames) pts += f.points.size();
  log::info(d.path, ": ", d.frames.size(), " frames (", d.source, ", ", d.frequency, "), ", pts,
            " points kept, ", dropped.projected, " range-image returns; dropped from the range images (and, out of range, from the points): ",
            dropped.non_finite, " NaN/Inf (also dropped from the points), ", dropped.beyond_range,
            " at >= ", d.sensor.max_range_m, " m, ", dropped.below_min_range, " within min range, ",
            dropped.out_of_fov, " outside the field of view, ", dropped.occluded,
            " behind a nearer return");
}

}  // namespace detail
}  // namespace sgnlf
