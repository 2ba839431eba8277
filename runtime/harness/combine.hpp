// One table from partial runs (results/schema.md "Combined tables"): results.json files of the
// same table, scale and data, each holding some of the rows (sgnlf bench --rows), sequences or
// seeds, made at different commits, are combined into one results.json with every row of
// this build's table definition. Runs are matched per cell (row × sequence × seed): a cell run
// with several seeds becomes a several-seed entry as `bench --seeds` writes it. A row no input ran is "not_run" (or "not_implemented" when
// this build lacks the method); every run entry names its source file (commit, command,
// created time, harness config hash), and a run whose config hash is not the method×scale's
// current resolved one is flagged "stale". `sgnlf merge --out DIR RESULTS...` calls this.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "harness/runner.hpp"

namespace sgnlf::harness {

struct CombineOptions {
  // Two inputs with different results for the same row × sequence × seed are refused unless this is
  // set: then the later input (command-line order) replaces the earlier one, and the
  // replacement is recorded in combined_from.superseded.
  bool later_wins = false;
  // Inputs of another table (same scale and data) are accepted: their runs of this table's
  // rows on the sequences both tables define alike are taken (the same config hash makes them
  // the same cells); everything else of them is left out and listed in combined_from.shared.
  bool share_cells = false;
};

// True when `results` is an sgnlf.results table (a `sgnlf bench` or combined output).
bool is_results_table(const Json& results);

// Where a results table's runs come from, as combined_from.files[] records it: {file, command,
// created_utc, config_hash, git {sha, dirty}, build_git_sha, build_git_dirty,
// opencl {device, driver_version}}.
Json source_description(const std::string& path, const Json& results);

// Combines results tables ({path, json}). Uses hooks.implemented (rows no input ran) and
// hooks.config_hash (stale runs; unset or "" = unknown, stale is then null). ConfigError naming
// the files when they differ in table, scale or data, when a row or sequence is not in this
// build's table, and when two inputs disagree on a cell (row × sequence × seed) without
// `later_wins`.
Json combine_tables(const std::vector<std::pair<std::string, Json>>& inputs,
                    const CombineOptions& opt, const BenchHooks& hooks, const std::string& command,
                    const std::string& out_dir);

}  // namespace sgnlf::harness
