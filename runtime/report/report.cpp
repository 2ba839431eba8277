#include "report/report.hpp"

#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "report/html.hpp"
#include "report/page.hpp"
#include "report/run_sections.hpp"

namespace sgnlf::report {
namespace fs = std::filesystem;

FolderKind folder_kind(const std::string& dir) {
  if (!fs::is_directory(dir)) throw IoError("report: " + dir + ": no such folder");
  if (fs::exists(fs::path(dir) / "run.json")) return FolderKind::run;
  if (fs::exists(fs::path(dir) / "results.json")) return FolderKind::bench;
  throw IoError("report: " + dir +
                ": neither a run folder (no run.json) nor a bench folder (no results.json)");
}

std::string run_body(const RunFolder& run, const std::string& renders_dir, int max_images) {
  return context_section(run) + metrics_section(run) + anatomy_section(run, max_images) +
         curves_section(run) + trajectory_section(run) +
         renders_section(run, renders_dir, max_images);
}

std::string build_report(const std::string& dir, const ReportOptions& opt) {
  require(opt.max_images >= 0, "report: max_images must be >= 0");
  if (folder_kind(dir) == FolderKind::bench) {
    if (!opt.renders_dir.empty())
      throw ConfigError("report: --renders applies to a run folder; " + dir +
                        " is a bench folder (each run's own renders/ is used)");
    return build_bench_report(dir, opt);
  }
  const RunFolder run = load_run_folder(dir);
  std::string renders = opt.renders_dir;
  if (renders.empty() && fs::is_directory(run.file("renders"))) renders = run.file("renders");
  else if (!renders.empty() && !fs::is_directory(renders))
    throw IoError("report: --renders " + renders + ": no such folder");
  const std::string title = run.run.value("method", std::string("run")) + " on " +
                            fs::path(run.run.value("dataset", dir)).filename().string();
  return html_page("sgnlf report: " + title,
                   "<h1>" + escape(title) + "</h1>\n<p><code>" + escape(dir) + "</code></p>\n" +
                       run_body(run, renders, opt.max_images));
}

std::string write_report(const std::string& dir, const std::string& out,
                         const ReportOptions& opt) {
  const std::string html = build_report(dir, opt);
  const std::string path = out.empty() ? (fs::path(dir) / "report.html").string() : out;
  std::ofstream f(path, std::ios::binary);
  if (!f) throw IoError("report: cannot write " + path);
  f << html;
  f.close();
  if (!f) throw IoError("report: error while writing " + path);
  return path;
}

}  // namespace sgnlf::report
