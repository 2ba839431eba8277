// A small synthetic run folder for the report tests: every file `sgnlf report` reads, written
// here (JSON, JSON lines, TUM trajectories, SVG pictures, PNG renders via io::write_png), with a
// dataset name that needs HTML escaping.
#pragma once
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "io/png_writer.hpp"
#include "io/trajectory_io.hpp"
#include "support/files.hpp"

namespace sgnlf::test {

inline const std::string kNastyName = "seq <b>&\"x'";

inline void write_text(const std::string& path, const std::string& text) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

inline Json metric_block(double s) {
  return Json{{"cd", 0.2 * s}, {"fscore", 0.9 / s}, {"depth_rmse", 3.0 * s},
              {"depth_psnr", 27.0 / s}, {"intensity_psnr", 19.0 / s}, {"raydrop_f1", 0.93 / s}};
}

struct RunFixtureOptions {
  bool top_view = true;  // trajectories/top_view.svg, else only the TUM files
  bool renders = true;   // renders/3.png and renders/7.png
};

// Writes the folder and returns the PNG paths of its renders, in frame order.
inline std::vector<std::string> write_run_fixture(const std::string& dir,
                                                  const RunFixtureOptions& o = {}) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  write_json_file(dir + "/run.json",
                  Json{{"method", "sg-nlf"}, {"preset", "quick"}, {"seed", 7},
                       {"dataset", "/data/" + kNastyName}, {"device", ""},
                       {"config_hash", "0123456789abcdef"},
                       {"config", {{"method", "sg-nlf"}, {"note", "a <tag> & more"}}}});
  write_json_file(dir + "/summary.json",
                  Json{{"end_step", 100}, {"train_frames", 8}, {"test_frames", 2},
                       {"device", "[0] Test Platform / test-device (CPU)"},
                       {"pose_metrics", {{"ate_m", 0.08}, {"rpe_t_cm", 3.8}, {"rpe_r_deg", 0.07}}},
                       {"initial_pose_metrics", {{"ate_m", 3.25}, {"rpe_t_cm", 461.0}, {"rpe_r_deg", 19.4}}}});
  Json per_frame = Json::array(), naive_frames = Json::array();
  for (int f : {3, 7}) {
    Json m = metric_block(f == 3 ? 1.0 : 1.1), n = metric_block(2.0);
    m["frame"] = f, n["frame"] = f;
    per_frame.push_back(m), naive_frames.push_back(n);
  }
  write_json_file(dir + "/metrics.json",
                  Json{{"dataset", kNastyName}, {"step", 100}, {"metrics", metric_block(1.05)},
                       {"per_frame", per_frame},
                       {"naive_baseline", {{"metrics", metric_block(2.0)}, {"per_frame", naive_frames}}},
                       {"pose_metrics", {{"ate_m", 0.0817}, {"rpe_t_cm", 3.843}, {"rpe_r_deg", 0.0793}}},
                       {"initial_pose_metrics", {{"ate_m", 3.2526}, {"rpe_t_cm", 461.56}, {"rpe_r_deg", 19.43}}}});
  std::string log;
  for (int s = 1; s <= 100; s += 33)
    log += Json{{"step", s}, {"lr", 0.01 / s},
                {"loss", {{"total", 70.0 / s}, {"depth", 69.0 / s}, {"grad", 0.0}}},
                {"pose", {{"ate_m", 0.25 / s}}}}.dump() + "\n";
  write_text(dir + "/train_log.jsonl", log + "{\"step\": 101, \"lo");  // a log still being written
  write_text(dir + "/geometric_log.jsonl",
             Json{{"step", 10}, {"after", {{"ate_m", 0.2}}}}.dump() + "\n" +
                 Json{{"step", 40}, {"after", {{"ate_m", 0.1}}}}.dump() + "\n");
  std::vector<Pose> gt(4, Pose::Identity()), opt(4, Pose::Identity());
  for (int k = 0; k < 4; ++k) gt[size_t(k)].translation() = Eigen::Vector3d(4.0 * k, 0.1 * k * k, 0);
  for (int k = 0; k < 4; ++k) opt[size_t(k)].translation() = Eigen::Vector3d(4.0 * k + 0.2, 0.1 * k * k, 0);
  fs::create_directories(dir + "/trajectories");
  io::write_tum_poses(dir + "/trajectories/gt.tum.txt", {0, 0.5, 1, 1.5}, gt);
  io::write_tum_poses(dir + "/trajectories/optimised.tum.txt", {0, 0.5, 1, 1.5}, opt);
  const std::string svg_open = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"40\" height=\"20\">";
  if (o.top_view)
    write_text(dir + "/trajectories/top_view.svg", svg_open + "<text>top view</text></svg>\n");
  write_text(dir + "/pose_graph/epoch_00005.svg", svg_open + "<text>epoch 5</text></svg>\n");
  write_text(dir + "/pose_graph/epoch_00010.svg", svg_open + "<text>epoch 10</text></svg>\n");
  write_json_file(dir + "/pose_graph/epoch_00010.json",
                  Json{{"edges", {{{"i", 0}, {"j", 1}, {"kept", true}, {"sequential", true}},
                                  {{"i", 0}, {"j", 3}, {"kept", true}, {"sequential", false}},
                                  {{"i", 1}, {"j", 3}, {"kept", false}, {"sequential", false}}}}});
  std::vector<std::string> pngs;
  if (!o.renders) return pngs;
  for (int f : {7, 3}) {  // written out of order: the page sorts by frame
    io::RgbImage img;
    img.height = 4 + f, img.width = 6;
    img.rgb.resize(size_t(img.height * img.width * 3));
    for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = uint8_t(i * 7 + f);
    const std::string p = dir + "/renders/" + std::to_string(f) + ".png";
    fs::create_directories(dir + "/renders");
    io::write_png(p, img);
    write_text(dir + "/renders/" + std::to_string(f) + "_gt.npy", "");
  }
  return {dir + "/renders/3.png", dir + "/renders/7.png"};
}

// The src attribute of every <img> tag, in page order.
inline std::vector<std::string> img_sources(const std::string& html) {
  std::vector<std::string> v;
  for (size_t p = html.find("<img"); p != std::string::npos; p = html.find("<img", p + 1)) {
    const size_t end = html.find('>', p);
    const std::string tag = html.substr(p, end - p);
    const size_t s = tag.find("src=\"");
    v.push_back(s == std::string::npos ? "" : tag.substr(s + 5, tag.find('"', s + 5) - s - 5));
  }
  return v;
}

inline size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

}  // namespace sgnlf::test
