// The small files of a table's runs, kept beside the committed table (issue 65 item 1) so that
// anyone can recompute a cell's pose and view metrics without its run folder:
//   <out>/runs/<method>/<sequence>/seed<k>/metrics.json, summary.json and
//   trajectories/{initial,optimised,gt}.kitti.txt (gt: the reference; pose-free runs only:
//   a method trained on the reference poses writes no trajectories)
// copied from each run's folder (rows[].sequences[].run_dir, or each seed's runs[].run_dir) by
// `sgnlf merge --keep-run-files`, for the runs a merge takes from a new input (a bench output
// or cell file; a combined table's runs keep the files it already has).
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/config_fwd.hpp"

namespace sgnlf::harness {

// The files copied (run-folder relative); the larger are left out, with a note.
const std::vector<std::string>& kept_run_file_names();

struct KeptRunFiles {
  std::vector<std::string> copied;  // destination paths
  std::vector<std::string> notes;   // files left out and why
};

// `results` is the merge's output, `inputs` ({path, json}) what it merged, `out_dir` the
// merge's --out. A run folder is looked for at its run_dir, then (when it lies under the
// input's out_dir) under the folder of the input file. ConfigError naming the run when its
// folder or its metrics.json / summary.json is missing; checked for every run before anything
// is copied. A destination folder already there is replaced (the merge replaced that run).
KeptRunFiles keep_run_files(const Json& results, const std::vector<std::pair<std::string, Json>>& inputs,
                            const std::string& out_dir, uintmax_t max_bytes = 200 * 1024);

}  // namespace sgnlf::harness
