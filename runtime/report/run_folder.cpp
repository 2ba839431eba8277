#include "report/run_folder.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/config.hpp"
#include "core/error.hpp"
#include "report/html.hpp"

namespace sgnlf::report {
namespace fs = std::filesystem;
namespace {

Json optional_json(const std::string& path) {
  return fs::exists(path) ? load_json_file(path) : Json(nullptr);
}

}  // namespace

std::string RunFolder::file(const std::string& name) const {
  return (fs::path(path) / name).string();
}

RunFolder load_run_folder(const std::string& path) {
  if (!fs::is_directory(path)) throw IoError("report: " + path + ": no such folder");
  RunFolder r;
  r.path = path;
  const std::string manifest = r.file("run.json");
  if (!fs::exists(manifest))
    throw IoError("report: " + path +
                  ": not a run folder (no run.json) nor a bench folder (no results.json)");
  r.run = load_json_file(manifest);
  if (!r.run.is_object()) throw IoError("report: " + manifest + ": not a JSON object");
  r.summary = optional_json(r.file("summary.json"));
  r.metrics = optional_json(r.file("metrics.json"));
  r.metrics_fast = optional_json(r.file("metrics-fast.json"));
  r.reconstruct = optional_json(r.file("reconstruct.json"));
  r.anatomy = optional_json(r.file("anatomy.json"));
  return r;
}

std::vector<Json> read_json_lines(const std::string& path) {
  std::vector<Json> out;
  if (!fs::exists(path)) return out;
  const std::string text = read_bytes(path);
  std::istringstream in(text);
  std::string line;
  int n = 0;
  size_t consumed = 0;
  while (std::getline(in, line)) {
    ++n;
    consumed += line.size() + 1;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const bool unterminated = consumed > text.size();
    Json j = Json::parse(line, nullptr, false);
    if (j.is_discarded()) {
      if (unterminated) break;
      throw IoError("report: " + path + ":" + std::to_string(n) + ": not a JSON value");
    }
    out.push_back(std::move(j));
  }
  return out;
}

}  // namespace sgnlf::report
