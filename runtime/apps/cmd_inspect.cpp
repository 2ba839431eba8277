// `sgnlf inspect <dataset> [--json]`: what a dataset holds (frames, points per scan, range and
// intensity statistics, pose step lengths, split). Reads any layout load_dataset knows, a single
// scan file or a folder of scans (whose sensor, unless --sensor names one, is estimated from the
// scans and printed). --png/--npy/--ply write one frame's range image or points.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "apps/command.hpp"
#include "apps/sensor_rate_options.hpp"
#include "core/config.hpp"
#include "core/error.hpp"
#include "datasets/loader.hpp"
#include "io/cloud_writers.hpp"
#include "io/png_writer.hpp"
#include "io/range_array.hpp"

namespace sgnlf::app {
namespace {

struct Summary {
  double min = 0, mean = 0, max = 0;
  size_t n = 0;
};
Summary summarize(const std::vector<double>& v) {
  Summary s;
  if (v.empty()) return s;
  s.n = v.size();
  s.min = *std::min_element(v.begin(), v.end());
  s.max = *std::max_element(v.begin(), v.end());
  for (double x : v) s.mean += x / double(v.size());
  return s;
}
Json to_json(const Summary& s) { return Json{{"min", s.min}, {"mean", s.mean}, {"max", s.max}, {"count", s.n}}; }

// Share of the returns per range bin (edges in metres, the last bin open-ended).
const std::vector<double> kRangeEdges{0, 5, 10, 15, 20, 30, 40, 50, 60, 80};

Json range_histogram(const std::vector<double>& ranges) {
  std::vector<double> frac(kRangeEdges.size(), 0.0);
  for (double r : ranges) {
    size_t b = 0;
    while (b + 1 < kRangeEdges.size() && r >= kRangeEdges[b + 1]) ++b;
    frac[b] += 1.0 / double(ranges.size());
  }
  return Json{{"edges_m", kRangeEdges}, {"fraction", frac}};
}

Json inspect_json(const Dataset& d) {
  std::vector<double> npts, ranges, inten, steps, rot_steps, ret_frac;
  std::vector<double> row_returns(size_t(d.sensor.height), 0.0);
  for (size_t k = 0; k < d.frames.size(); ++k) {
    const auto& f = d.frames[k];
    npts.push_back(double(f.points.size()));
    size_t ret = 0;
    for (size_t i = 0; i < f.image.size(); ++i)
      if (f.image.range[i] > 0.f) {
        ++ret;
        row_returns[i / size_t(d.sensor.width)] += 1.0 / double(d.sensor.width * d.frames.size());
        ranges.push_back(f.image.range[i]);
        inten.push_back(f.image.intensity[i]);
      }
    ret_frac.push_back(f.image.size() ? double(ret) / double(f.image.size()) : 0.0);
    if (k > 0) {
      const Pose rel = d.frames[k - 1].T_world_lidar.inverse() * f.T_world_lidar;
      steps.push_back(rel.translation().norm());
      rot_steps.push_back(rotation_angle(rel.linear()) * 180.0 / M_PI);
    }
  }
  Json ids = Json::array();
  for (const auto& f : d.frames) ids.push_back(f.id);
  return Json{{"name", d.name}, {"source", d.source}, {"path", d.path}, {"frequency", d.frequency},
              {"sensor", sensor_to_json(d.sensor)}, {"frames", d.frames.size()}, {"frame_ids", ids},
              {"duration_s", d.frames.empty() ? 0.0 : d.frames.back().timestamp_s},
              {"points_per_scan", to_json(summarize(npts))},
              {"return_fraction", to_json(summarize(ret_frac))},
              {"drop_rate", 1.0 - summarize(ret_frac).mean},
              {"range_m", to_json(summarize(ranges))}, {"range_histogram", range_histogram(ranges)},
              {"return_fraction_by_row", row_returns}, {"intensity", to_json(summarize(inten))},
              {"pose_step_m", to_json(summarize(steps))}, {"pose_step_deg", to_json(summarize(rot_steps))},
              {"split", {{"train", d.split.train}, {"test", d.split.test}}}};
}

void print_summary(const std::string& label, const Json& s, const char* unit) {
  std::printf("  %-16s min %.4g  mean %.4g  max %.4g %s\n", label.c_str(), s["min"].get<double>(),
              s["mean"].get<double>(), s["max"].get<double>(), unit);
}

const Registrar reg("inspect", "Describe a dataset (synthetic, KITTI-360, KITTI odometry, nuScenes, scans)", [](CLI::App& sub) {
  auto path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto opt = std::make_shared<LoadOptions>();
  auto sensor_rate = std::make_shared<SensorRateOptions>();
  auto png = std::make_shared<std::string>(), npy = std::make_shared<std::string>(), ply = std::make_shared<std::string>();
  auto frame = std::make_shared<int>(0);
  auto repeat = std::make_shared<int>(3);
  sub.add_option("dataset", *path, "Dataset folder, scan folder or scan file")->required();
  sub.add_flag("--json", *json, "Print JSON");
  sub.add_option("--sequence", opt->sequence, "Sequence / drive / scene");
  sub.add_option("--start", opt->start, "First frame id");
  sub.add_option("--frames", opt->frames, "Number of frames");
  sub.add_option("--stride", opt->stride, "Frame stride of the native stream");
  sensor_rate->add(sub);
  sub.add_option("--frame", *frame, "Frame index (into the loaded frames) for --png/--npy/--ply");
  sub.add_option("--png", *png, "Write the frame's range image picture (depth turbo, intensity, mask)");
  sub.add_option("--row-repeat", *repeat, "Rows repeated in the picture");
  sub.add_option("--npy", *npy, "Write the frame's range image as .npy (H, W, 3)");
  sub.add_option("--ply", *ply, "Write the frame's points as binary PLY");
  return std::function<int()>([=] {
    sensor_rate->apply(*opt);
    const Dataset d = load_dataset(*path, *opt);
    if (*frame < 0 || size_t(*frame) >= d.frames.size())
      throw ConfigError("inspect: --frame " + std::to_string(*frame) + " outside 0.." + std::to_string(d.frames.size() - 1));
    const Frame& f = d.frames[size_t(*frame)];
    io::RangePictureOptions po;
    po.row_repeat = *repeat;
    po.max_range_m = d.sensor.max_range_m;
    if (!png->empty()) io::write_png(*png, io::range_image_picture(f.image, po));
    if (!npy->empty()) io::write_range_npy(*npy, f.image);
    if (!ply->empty()) io::write_ply(*ply, f.points);
    const Json j = inspect_json(d);
    if (*json) {
      std::cout << j.dump(2) << "\n";
      return 0;
    }
    std::printf("%s (%s, %s frequency) at %s\n", d.name.c_str(), d.source.c_str(), d.frequency.c_str(), d.path.c_str());
    std::printf("  sensor %s: %dx%d, fov_up %.2f deg, fov %.2f deg, range %.1f-%.1f m, %.1f Hz\n", d.sensor.name.c_str(),
                d.sensor.height, d.sensor.width, d.sensor.fov_up_deg, d.sensor.fov_deg, d.sensor.min_range_m,
                d.sensor.max_range_m, d.sensor.rate_hz);
    if (d.sensor.name == "estimated")  // save it to pass as --sensor FILE
      std::printf("  estimated from the scans; as a sensor file: %s\n", sensor_to_json(d.sensor).dump().c_str());
    std::printf("  %zu frames (ids %d..%d), %.2f s\n", d.frames.size(), d.frames.front().id, d.frames.back().id,
                j["duration_s"].get<double>());
    print_summary("points/scan", j["points_per_scan"], "");
    print_summary("return fraction", j["return_fraction"], "");
    std::printf("  %-16s %.4f\n", "drop rate", j["drop_rate"].get<double>());
    print_summary("range", j["range_m"], "m");
    const auto& h = j["range_histogram"];
    std::printf("  %-16s", "range histogram");
    for (size_t b = 0; b < kRangeEdges.size(); ++b)
      std::printf(" %g%s:%.3f", kRangeEdges[b], b + 1 < kRangeEdges.size() ? "" : "+", h["fraction"][b].get<double>());
    std::printf("\n  %-16s", "returns by row");
    for (const auto& x : j["return_fraction_by_row"]) std::printf(" %.2f", x.get<double>());
    std::printf("\n");
    print_summary("intensity", j["intensity"], "");
    if (d.frames.size() > 1) {
      print_summary("pose step", j["pose_step_m"], "m");
      print_summary("pose rotation", j["pose_step_deg"], "deg");
    }
    std::string test;
    for (int t : d.split.test) test += " " + std::to_string(t);
    std::printf("  split: %zu train, %zu test (frames%s)\n", d.split.train.size(), d.split.test.size(), test.c_str());
    return 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
