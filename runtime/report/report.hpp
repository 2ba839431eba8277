// `sgnlf report`: one self-contained HTML page (report/page.hpp) of a run folder (run.json) or
// of a bench output folder (results.json, with runs/<method>/<sequence>/ inside). Pictures are
// embedded as data: URIs, curves drawn as inline SVG; the page loads nothing.
#pragma once
#include <string>

#include "report/run_folder.hpp"

namespace sgnlf::report {

struct ReportOptions {
  std::string renders_dir;  // a run's renders; empty: RUN/renders when it exists
  int max_images = 24;      // pictures embedded per run at most
};

enum class FolderKind { run, bench };
// IoError naming the path when it is not a folder or holds neither run.json nor results.json.
FolderKind folder_kind(const std::string& dir);

// The sections of one run (context, metrics, curves, trajectories, renders), no page around.
std::string run_body(const RunFolder& run, const std::string& renders_dir, int max_images);

// The whole page of a run or bench folder.
std::string build_report(const std::string& dir, const ReportOptions& opt = {});
std::string build_bench_report(const std::string& dir, const ReportOptions& opt = {});

// Writes build_report(dir) to `out` (default <dir>/report.html) and returns the path written.
std::string write_report(const std::string& dir, const std::string& out = "",
                         const ReportOptions& opt = {});

}  // namespace sgnlf::report
