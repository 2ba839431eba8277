// What the report reads from a run folder (docs/training-and-run-folders.md,
// pipeline/run/run_dir.hpp): run.json (required), summary.json and metrics.json /
// metrics-fast.json and anatomy.json when present, reconstruct.json in a `sgnlf reconstruct` folder, and the
// JSON-lines logs.
#pragma once
#include <string>
#include <vector>

#include "core/config.hpp"

namespace sgnlf::report {

struct RunFolder {
  std::string path;
  Json run;                           // run.json
  Json summary = nullptr;             // summary.json (after training), else null
  Json metrics = nullptr;             // metrics.json (after `sgnlf eval`), else null
  Json metrics_fast = nullptr;        // metrics-fast.json (`sgnlf eval --renderer fast`), else null
  Json reconstruct = nullptr;         // reconstruct.json (`sgnlf reconstruct`), else null
  Json anatomy = nullptr;             // anatomy.json (`sgnlf anatomy`), else null
  std::string file(const std::string& name) const;  // path/name
};

// IoError naming the folder when it does not exist or holds no run.json; a present file that
// is not valid JSON is an error naming it too.
RunFolder load_run_folder(const std::string& path);

// One JSON value per line; empty when the file does not exist. A malformed line is an IoError
// "file:line"; only an unterminated last line (a log still being written) is skipped.
std::vector<Json> read_json_lines(const std::string& path);

}  // namespace sgnlf::report
