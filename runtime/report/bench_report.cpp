// The report of a bench output folder (report.hpp): results.json's table (rows' means beside
// the paper's numbers), a table per sequence with the naive baseline, and a section per run
// folder found under runs/<method>/<sequence>/.
#include <algorithm>
#include <filesystem>

#include "core/config.hpp"
#include "core/json_lookup.hpp"
#include "report/html.hpp"
#include "report/page.hpp"
#include "report/report.hpp"
#include "report/run_sections.hpp"

namespace sgnlf::report {
namespace fs = std::filesystem;
namespace {

// Null for a missing key or a non-object (core/json_lookup.hpp): never throws.
constexpr auto at = &member_or_null;

std::string str(const Json& j, const std::string& k) {
  const Json& v = at(j, k);
  return v.is_string() ? v.get<std::string>() : v.is_null() ? "" : v.dump();
}

std::vector<std::string> columns(const Json& r) {
  std::vector<std::string> c;
  for (const char* k : {"columns", "extra_columns"})
    for (const auto& x : at(r, k).is_array() ? r[k] : Json::array())
      if (x.is_string()) c.push_back(x.get<std::string>());
  return c;
}

std::string status_text(const std::string& s) {
  if (s == "not_implemented") return "not implemented";
  if (s == "skipped") return "not run (--rows)";
  return s.empty() ? "—" : s;
}

std::string main_table(const Json& r, const std::vector<std::string>& cols) {
  std::vector<std::string> head = {"method"};
  for (const auto& c : cols) head.push_back(escape(metric_header(c)));
  std::vector<std::vector<std::string>> rows;
  for (const auto& row : at(r, "rows").is_array() ? r["rows"] : Json::array()) {
    const bool ok = str(row, "status") == "ok";
    std::string label = escape(str(row, "label").empty() ? str(row, "method") : str(row, "label"));
    if (!ok) label += "<br><small>" + escape(status_text(str(row, "status"))) + "</small>";
    std::vector<std::string> line = {label};
    for (const auto& c : cols) {
      std::string cell = escape(metric_value(c, ok ? at(at(row, "mean"), c) : Json()));
      Json paper = at(at(row, "paper"), c);
      std::string mark;
      if (paper.is_null()) paper = at(at(row, "paper_unverified"), c), mark = "†";
      if (paper.is_number())
        cell += "<br><small>paper " + escape(metric_value(c, paper)) + mark + "</small>";
      line.push_back(cell);
    }
    rows.push_back(std::move(line));
  }
  return html_table(head, rows, "num");
}

// One sequence: each row's run, then the naive baseline (the first run that reports it).
std::string sequence_table(const Json& r, const std::string& seq, const std::vector<std::string>& cols,
                           const std::string& bench_dir) {
  std::vector<std::string> head = {"method"};
  for (const auto& c : cols) head.push_back(escape(metric_header(c)));
  std::vector<std::vector<std::string>> rows;
  Json naive;
  for (const auto& row : at(r, "rows").is_array() ? r["rows"] : Json::array())
    for (const auto& s : at(row, "sequences").is_array() ? row["sequences"] : Json::array()) {
      if (str(s, "sequence") != seq) continue;
      const std::string method = str(row, "method");
      std::string label = escape(str(row, "label").empty() ? method : str(row, "label"));
      if (fs::exists(fs::path(bench_dir) / "runs" / method / seq / "run.json"))
        label = "<a href=\"#" + anchor_id("run-" + method + "-" + seq) + "\">" + label + "</a>";
      std::vector<std::string> line = {label};
      for (const auto& c : cols) {
        const Json& v = at(at(s, "metrics"), c).is_null() ? at(at(s, "pose_metrics"), c)
                                                          : at(at(s, "metrics"), c);
        line.push_back(escape(metric_value(c, v)));
      }
      rows.push_back(std::move(line));
      if (naive.is_null()) naive = at(at(s, "extra"), "naive_baseline");
    }
  if (naive.is_object()) {
    std::vector<std::string> line = {"<em>naive baseline</em>"};
    for (const auto& c : cols) line.push_back(escape(metric_value(c, at(naive, c))));
    rows.push_back(std::move(line));
  }
  if (rows.empty()) return "<p class=\"note\">No run of this sequence.</p>\n";
  return html_table(head, rows, "num");
}

}  // namespace

std::string build_bench_report(const std::string& dir, const ReportOptions& opt) {
  const Json r = load_json_file((fs::path(dir) / "results.json").string());
  const auto cols = columns(r);
  const std::string title = str(r, "title").empty() ? "bench " + dir : str(r, "title");
  std::string b = "<h1>" + escape(title) + "</h1>\n<p>Table <code>" + escape(str(r, "table")) +
                  "</code>, scale <code>" + escape(str(r, "scale")) + "</code>, " +
                  escape(str(r, "data")) + " data, created " + escape(str(r, "created_utc")) +
                  ".</p>\n<p>Command: <code>" + escape(str(r, "command")) + "</code></p>\n";

  // Run folders inside the bench folder, in name order.
  std::vector<fs::path> runs;
  if (fs::is_directory(fs::path(dir) / "runs"))
    for (const auto& m : fs::directory_iterator(fs::path(dir) / "runs"))
      if (m.is_directory())
        for (const auto& s : fs::directory_iterator(m.path()))
          if (fs::exists(s.path() / "run.json")) runs.push_back(s.path());
  std::sort(runs.begin(), runs.end());
  if (!runs.empty()) {
    b += "<nav><strong>Runs:</strong> ";
    for (const auto& p : runs) {
      const std::string name = p.parent_path().filename().string() + "/" + p.filename().string();
      b += "<a href=\"#" + anchor_id("run-" + p.parent_path().filename().string() + "-" +
                                     p.filename().string()) + "\">" + escape(name) + "</a>";
    }
    b += "</nav>\n";
  }
  b += "<section><h2>Table (mean over sequences)</h2>\n" + main_table(r, cols) +
       "<p class=\"note\">† paper number from third-party notes, not verified.</p>\n";
  for (const auto& s : at(r, "sequences").is_array() ? r["sequences"] : Json::array()) {
    const std::string name = str(s, "name");
    b += "<h3>Sequence " + escape(name) + "</h3>\n" + sequence_table(r, name, cols, dir);
  }
  if (at(r, "config").is_object()) b += json_details("bench config", r["config"]);
  if (at(r, "context").is_object()) b += json_details("run context (build, machine, OpenCL)", r["context"]);
  b += "</section>\n";

  for (const auto& p : runs) {
    const RunFolder run = load_run_folder(p.string());
    const std::string m = p.parent_path().filename().string(), s = p.filename().string();
    const std::string renders = fs::is_directory(p / "renders") ? (p / "renders").string() : "";
    b += "<article id=\"" + anchor_id("run-" + m + "-" + s) + "\"><h2 class=\"run\">Run " +
         escape(m + " / " + s) + "</h2>\n" + run_body(run, renders, opt.max_images) + "</article>\n";
  }
  if (runs.empty()) b += "<p class=\"note\">No run folders under runs/.</p>\n";
  return html_page("sgnlf report: " + title, b);
}

}  // namespace sgnlf::report
