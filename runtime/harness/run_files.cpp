#include "harness/run_files.hpp"

#include <filesystem>

#include "core/config.hpp"

namespace sgnlf::harness {
namespace fs = std::filesystem;
namespace {

using Inputs = std::vector<std::pair<std::string, Json>>;

struct RunToKeep {
  std::string method, sequence;
  uint64_t seed = 1;
  fs::path from, to;
};

// The inputs a run entry of the output may come from: for a combined table, the plain input
// its source describes (none when it was carried from an earlier combined table); else all.
std::vector<const std::pair<std::string, Json>*> new_inputs_of(const Json& results, const Json& e,
                                                                const Inputs& inputs) {
  std::vector<const std::pair<std::string, Json>*> v;
  if (!results.contains("combined_from")) {
    for (const auto& in : inputs) v.push_back(&in);
    return v;
  }
  const Json files = results["combined_from"].value("files", Json::array());
  const size_t k = e.value("source", size_t(0));
  if (k >= files.size()) return v;
  for (const auto& in : inputs)
    if (!in.second.contains("combined_from") && files[k].value("file", "") == in.first &&
        files[k].value("created_utc", "") == in.second.value("created_utc", ""))
      v.push_back(&in);
  return v;
}

// The run folder: run_dir as recorded (relative to where the merge runs), else the same place
// under an input's folder when run_dir lies under that input's out_dir (a moved output).
fs::path find_run_folder(const std::string& run_dir,
                         const std::vector<const std::pair<std::string, Json>*>& from) {
  if (fs::is_directory(run_dir)) return run_dir;
  for (const auto* in : from) {
    const std::string out = in->second.value("out_dir", "");
    if (out.empty()) continue;
    const fs::path rel = fs::path(run_dir).lexically_normal().lexically_relative(fs::path(out).lexically_normal());
    if (rel.empty() || *rel.begin() == "..") continue;
    const fs::path p = fs::path(in->first).parent_path() / rel;
    if (fs::is_directory(p)) return p;
  }
  return {};
}

// A run another table's combined input of this merge brought (merge --share-cells): that
// table's kept run files, runs/<method>/<sequence>/seed<k> beside its results.json; empty when
// the run did not come through an input of this merge or that folder is not there.
fs::path shared_run_folder(const Json& results, const Json& e, const Inputs& inputs,
                           const std::string& method, const std::string& sequence, uint64_t seed) {
  const Json files = results.contains("combined_from")
                         ? results["combined_from"].value("files", Json::array())
                         : Json::array();
  const size_t k = e.value("source", size_t(0));
  if (k >= files.size() || !files[k].contains("via")) return {};
  const std::string via = files[k].value("via", "");
  for (const auto& in : inputs)
    if (in.first == via && in.second.contains("combined_from")) {
      const fs::path p = fs::path(via).parent_path() / "runs" / method / sequence /
                         ("seed" + std::to_string(seed));
      if (fs::is_directory(p)) return p;
    }
  return {};
}

}  // namespace

const std::vector<std::string>& kept_run_file_names() {
  static const std::vector<std::string> names = {
      "metrics.json", "summary.json", "trajectories/initial.kitti.txt",
      "trajectories/optimised.kitti.txt", "trajectories/gt.kitti.txt"};
  return names;
}

KeptRunFiles keep_run_files(const Json& results, const Inputs& inputs, const std::string& out_dir,
                            uintmax_t max_bytes) {
  std::vector<RunToKeep> runs;
  for (const auto& row : results.value("rows", Json::array())) {
    if (row.value("status", "") != "ok") continue;
    const std::string m = row.value("method", "");
    for (const auto& e : row.value("sequences", Json::array())) {
      for (const auto& x : e.contains("runs") ? e["runs"] : Json::array({e})) {
        // A several-seed entry of a combined table names each seed's source (they may differ).
        const Json& src = x.contains("source") ? x : e;
        const auto from = new_inputs_of(results, src, inputs);
        RunToKeep k{m, e.value("sequence", ""), x.value("seed", uint64_t(1)), {}, {}};
        if (from.empty()) {  // carried: kept only when another table's input brought it
          k.from = shared_run_folder(results, src, inputs, m, k.sequence, k.seed);
          if (k.from.empty()) continue;
          k.to = fs::path(out_dir) / "runs" / m / k.sequence / ("seed" + std::to_string(k.seed));
          if (fs::exists(k.to) && fs::equivalent(k.from, k.to)) continue;
          runs.push_back(k);
          continue;
        }
        const std::string what = "merge --keep-run-files: " + m + " / " + k.sequence + " seed " +
                                 std::to_string(k.seed);
        const std::string run_dir = x.value("run_dir", "");
        k.from = find_run_folder(run_dir, from);
        if (k.from.empty())
          throw ConfigError(what + ": its run folder '" + run_dir +
                            "' is not there (nor under the folder of " + from.front()->first + ")");
        for (const char* f : {"metrics.json", "summary.json"})
          if (!fs::is_regular_file(k.from / f))
            throw ConfigError(what + ": " + (k.from / f).string() + " is missing");
        k.to = fs::path(out_dir) / "runs" / m / k.sequence / ("seed" + std::to_string(k.seed));
        runs.push_back(k);
      }
    }
  }
  KeptRunFiles kept;
  for (const auto& k : runs) {
    fs::remove_all(k.to);
    for (const auto& name : kept_run_file_names()) {
      const fs::path src = k.from / name, dst = k.to / name;
      if (!fs::is_regular_file(src)) {
        if (name.rfind("trajectories/", 0) == 0 && fs::is_directory(k.from / "trajectories"))
          kept.notes.push_back(src.string() + " is missing");
        continue;  // no trajectories folder: a method on the reference poses writes none
      }
      const uintmax_t bytes = fs::file_size(src);
      if (bytes > max_bytes) {
        kept.notes.push_back(src.string() + " left out: " + std::to_string(bytes) + " bytes, over " +
                             std::to_string(max_bytes));
        continue;
      }
      fs::create_directories(dst.parent_path());
      fs::copy_file(src, dst, fs::copy_options::overwrite_existing);
      kept.copied.push_back(dst.string());
    }
  }
  return kept;
}

}  // namespace sgnlf::harness
