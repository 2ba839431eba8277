// The pictures of a run's report (run_sections.hpp): trajectories and pose graph, and the
// rendered vs observed range images, all embedded as data: URIs so the page stands alone.
#include <algorithm>
#include <filesystem>

#include "core/config.hpp"
#include "io/trajectory_io.hpp"
#include "report/html.hpp"
#include "report/run_sections.hpp"
#include "report/svg_chart.hpp"

namespace sgnlf::report {
namespace fs = std::filesystem;
namespace {

// Files of `dir` ending in `ext`, sorted by their numeric stem when both are numbers, else by name.
std::vector<fs::path> files_with(const std::string& dir, const std::string& ext) {
  std::vector<fs::path> v;
  if (!fs::is_directory(dir)) return v;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ext) v.push_back(e.path());
  auto numeric = [](const fs::path& p) {
    const std::string s = p.stem().string();
    return !s.empty() && s.size() < 10 && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  std::sort(v.begin(), v.end(), [&](const fs::path& a, const fs::path& b) {
    if (numeric(a) && numeric(b)) return std::stol(a.stem().string()) < std::stol(b.stem().string());
    if (numeric(a) != numeric(b)) return numeric(a);
    return a.filename() < b.filename();
  });
  return v;
}

// Top view drawn from the TUM files when the run has no top_view.svg.
std::string drawn_top_view(const RunFolder& r) {
  const std::pair<const char*, const char*> files[] = {
      {"gt", "#2ca02c"}, {"initial", "#d62728"}, {"optimised", "#1f77b4"}};
  std::vector<ChartSeries> series;
  for (const auto& [name, colour] : files) {
    const std::string p = r.file(std::string("trajectories/") + name + ".tum.txt");
    if (!fs::exists(p)) continue;
    ChartSeries s{name, colour, {}, {}, true};
    for (const auto& [t, pose] : io::read_tum_poses(p)) {
      s.x.push_back(pose.translation().x());
      s.y.push_back(pose.translation().y());
    }
    series.push_back(std::move(s));
  }
  if (series.empty()) return "";
  return svg_chart(series, {"Trajectories from above (TUM files; metres, not aligned)", "x (m)",
                            "y (m)", false, true, 640, 480});
}

std::string pose_graph_summary(const std::string& path) {
  const Json g = load_json_file(path);
  if (!g.is_object() || !g.contains("edges") || !g["edges"].is_array()) return "";
  int kept = 0, loops = 0;
  for (const auto& e : g["edges"]) {
    const bool k = e.value("kept", false);
    kept += k;
    loops += k && !e.value("sequential", true);
  }
  return "<p>" + std::to_string(g["edges"].size()) + " edges, " + std::to_string(kept) +
         " kept, of which " + std::to_string(loops) + " non-sequential (pose_graph/" +
         escape(fs::path(path).filename().string()) + ").</p>\n";
}

}  // namespace

std::string trajectory_section(const RunFolder& r) {
  std::string o = "<section><h2>Trajectories and pose graph</h2>\n";
  const std::string top = r.file("trajectories/top_view.svg");
  if (fs::exists(top)) o += "<figure>" + embedded_img(top, "image/svg+xml", "trajectories from above") +
                            "<figcaption>trajectories/top_view.svg</figcaption></figure>\n";
  else if (std::string d = drawn_top_view(r); !d.empty()) o += d;
  else o += "<p class=\"note\">No trajectories in the run folder.</p>\n";

  const auto graphs = files_with(r.file("pose_graph"), ".svg");
  if (!graphs.empty()) {
    const fs::path& last = graphs.back();
    const fs::path json = fs::path(last).replace_extension(".json");
    if (fs::exists(json)) o += pose_graph_summary(json.string());
    o += "<figure>" + embedded_img(last.string(), "image/svg+xml", "pose graph") + "<figcaption>pose_graph/" +
         escape(last.filename().string()) + " (latest of " + std::to_string(graphs.size()) +
         ")</figcaption></figure>\n";
  } else {
    o += "<p class=\"note\">No pose-graph pictures (pose_graph/*.svg).</p>\n";
  }
  return o + "</section>\n";
}

std::string renders_section(const RunFolder& r, const std::string& renders_dir, int max_images) {
  std::string o = "<section><h2>Rendered vs observed range images</h2>\n";
  const auto pngs = renders_dir.empty() ? std::vector<fs::path>{} : files_with(renders_dir, ".png");
  if (pngs.empty()) {
    return o + "<p class=\"note\">No renders" +
           (renders_dir.empty() ? std::string(" (no renders/ folder in the run; give --renders DIR)")
                                : " in " + escape(renders_dir)) +
           ": <code>sgnlf render " + escape(r.path) + "</code> writes them.</p></section>\n";
  }
  o += "<p>From " + escape(renders_dir) + ". Each picture: the rendering (depth, intensity, "
       "return mask) above the observed scan; novel views show the rendering alone.</p>\n<div class=\"renders\">\n";
  const Json& frames = r.metrics.is_object() ? r.metrics.value("per_frame", Json::array()) : Json();
  int shown = 0;
  for (const auto& p : pngs) {
    if (shown++ == max_images) break;
    const std::string stem = p.stem().string();
    // A test frame's picture (pipeline/run/session.cpp render_run) stacks the rendering above
    // the observed scan and has its _gt.npy beside it; a novel view's is the rendering alone.
    const bool pair = fs::exists(p.parent_path() / (stem + "_gt.npy"));
    std::string caption = (pair ? "frame " + stem : stem) + " (" + p.filename().string() + ")";
    for (const auto& f : frames.is_array() ? frames : Json::array())
      if (f.value("frame", Json()).dump() == stem)
        caption += ": depth PSNR " + metric_value("depth_psnr", f.value("depth_psnr", Json())) +
                   " dB, CD " + metric_value("cd", f.value("cd", Json())) + " m²";
    o += "<figure><div class=\"pair\">" + embedded_img(p.string(), "image/png", p.filename().string());
    if (pair) o += "<span class=\"tag top\">rendered</span><span class=\"tag bottom\">observed</span>";
    o += "</div><figcaption>" + escape(caption) + "</figcaption></figure>\n";
  }
  o += "</div>\n";
  if (int(pngs.size()) > max_images)
    o += "<p class=\"note\">" + std::to_string(pngs.size() - max_images) +
         " more pictures not embedded (--max-images).</p>\n";
  return o + "</section>\n";
}

}  // namespace sgnlf::report
