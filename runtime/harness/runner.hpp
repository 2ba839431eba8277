// The table runner behind `sgnlf bench`: every row (method) of a table on every sequence of
// the chosen scale, with fixed seeds, producing the results JSON of results/schema.md.
// Training and data are injected (BenchHooks), so the runner is testable without them; the
// app passes default_hooks() (wiring.hpp), which calls pipeline::run_method.
#pragma once
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "harness/tables.hpp"
#include "pipeline/run/method.hpp"

namespace sgnlf::harness {

struct BenchOptions {
  std::string table;
  std::string scale = "smoke";
  std::string data_root;  // "" = built-in synthetic twins
  // Folder holding real datasets for the sequences of a synthetic scale that set `real_dir`
  // (SequenceDef); "" = default_real_root(). Such a sequence is read from
  // <real_root>/<real_dir> when that folder exists and skipped (recorded) otherwise. Not part
  // of to_json() (a machine's path; the twins' numbers do not depend on it): results record it
  // at the top level (`real_root`, results/schema.md).
  std::string real_root;
  std::string out_dir;
  std::string device;     // OpenCL device spec ("" = default)
  uint64_t seed = 1;
  // --seeds: every cell runs with each of these (results/schema.md "Several seeds"); empty =
  // the one `seed`. One element is the same as --seed (a single-seed result, unchanged).
  std::vector<uint64_t> seeds;
  bool roofline = true;   // measure and record the device's roofline
  std::string command;    // the command line, recorded verbatim
  // Subsets (empty = all): rows outside `rows` are kept in the result as status "skipped";
  // `sequences` narrows the scale's sequences (means are over the ones run). Recorded in the
  // config only when non-empty, so a full table's config_hash does not change.
  std::vector<std::string> rows, sequences;
  void validate() const;
  std::vector<uint64_t> seed_list() const;  // `seeds`, or {seed} when empty
  Json to_json() const;   // the resolved harness config (without `command`, `out_dir`, `real_root`)
  std::string resolved_real_root() const;  // real_root, or default_real_root() when empty
};

// $SGNLF_SHARED_DIR/data/real when that variable is set, else "../shared/data/real" (relative
// to the working directory: the shared folder beside a checkout run from its root).
std::string default_real_root();

// The folder a sequence's data is read from in its own layout: --data-root for the real
// windows, <resolved_real_root()>/<real_dir> for a real sequence of a synthetic scale, ""
// for a synthetic twin (simulated).
std::string sequence_data_root(const SequenceDef& s, const BenchOptions& opt);

// A sequence ready on disk: the folder the pipeline reads and a description of it
// (name, source, frames, split, sensor, seed... see results/schema.md "dataset").
struct PreparedSequence {
  std::string dataset_dir;
  Json dataset = Json::object();
  Json overrides = Json::object();  // merged into MethodRequest::overrides (e.g. window)
  double seconds = 0.0;             // time spent preparing (simulation / loading)
};

struct BenchHooks {
  std::function<bool(const std::string& method)> implemented;
  std::function<pipeline::MethodResult(const pipeline::MethodRequest&)> run;
  // For a real sequence of a synthetic scale (`real_dir`), the runner passes options whose
  // data_root is the resolved folder, so the hook loads it like a --data-root window.
  std::function<PreparedSequence(const SequenceDef&, const BenchOptions&,
                                 const std::string& dir)> prepare;
  // What the metrics mean (metrics::definitions()), recorded as "metric_definitions".
  std::function<Json()> metric_definitions;
  // The resolved config hash a method's run at a scale has in this build (16 hex digits, as
  // rows[].sequences[].config_hash; tests/pipeline/config_hashes.json), "" when unknown. Used
  // by `sgnlf merge` of results tables to flag runs made with another config as stale.
  std::function<std::string(const std::string& method, const std::string& scale)> config_hash;
};

// A cell: one independent run of a table (row × sequence × seed), the unit of
// `sgnlf bench --cells` / `--cell K` and `sgnlf merge` (harness/cells.hpp).
struct Cell {
  size_t index = 0;
  std::string method, sequence;
  uint64_t seed = 1;
};

// What a table run will do, fixed before anything runs: per table row its state ("run",
// "skipped" by --rows, "not_implemented"), the sequences (after --sequences; a real sequence
// of a synthetic scale is listed whether or not its folder is there: a cell finds out), the
// seeds, and the cells: rows to run × sequences × seeds, in that order (row-major), indexed.
struct TablePlan {
  TableDef table;
  std::vector<SequenceDef> sequences;
  std::vector<std::string> row_state;
  std::vector<uint64_t> seeds;
  std::vector<Cell> cells;
  Json to_json() const;     // {rows: [{method, state}], sequences: [names], seeds, cells: count}
  std::string hash() const; // config_hash() of to_json(): equal plans, equal cell indices
};
TablePlan plan_table(const BenchOptions& opt, const BenchHooks& hooks);

// The outcome of one cell (results/schema.md "Cells"), as run_table and a cell file keep it.
struct CellOutcome {
  bool present = false;
  // ok | failed | not_implemented | missing (a real sequence's folder is not there) |
  // unloadable (it is there and does not load)
  std::string status;
  std::string error;      // failed: the error; missing / unloadable: the reason
  std::string data_path;  // a real sequence: the folder it is read from
  Json entry;             // ok: the run's rows[].sequences[] entry
  Json dataset;           // the prepared sequence's description (null when not prepared)
  double prepare_s = -1;  // >= 0: this cell prepared the sequence, in that many seconds
  Json to_json() const;
  static CellOutcome from_json(const Json& j, const std::string& where);  // ConfigError
};

// Runs one cell: prepares its sequence (unless `cache` has it) and trains + evaluates; the
// run folder's summary.json records `context` (the bench's context block) as where it ran.
// Failures are recorded in the outcome, not thrown.
CellOutcome execute_cell(const BenchOptions& opt, const BenchHooks& hooks, const TablePlan& plan,
                         const Cell& cell, std::map<std::string, PreparedSequence>& cache,
                         const Json& context);

// The table's results JSON from the cells' outcomes (indexed like plan.cells; a cell may be
// absent only after its row stopped or its sequence was skipped). Replays the one-process
// order, so that the cells run apart and merged give the same rows as run_table.
struct TableHeader {
  Json config;  // BenchOptions::to_json()
  std::string command, out_dir, real_root;
  bool real = false;  // --data-root
  Json metric_definitions, context;
  double total_s = 0;
  long peak_rss_kib = 0;
};
Json assemble_table(const TablePlan& plan, const std::vector<CellOutcome>& outcomes,
                    const TableHeader& header);

// Runs the table; `context` is the context block (context_block() + roofline), copied into
// the result. Failures of single runs are recorded in their row (status "failed") and the
// table goes on. A real sequence of a synthetic scale whose folder is missing is skipped with
// a warning and listed in `skipped_sequences` (ConfigError when --sequences named it or no
// sequence is left). Writes nothing itself; see write_outputs().
Json run_table(const BenchOptions& opt, const BenchHooks& hooks, Json context);

// Writes <out>/results.json and <out>/table.md; returns their paths.
std::pair<std::string, std::string> write_outputs(const Json& results, const std::string& out_dir);

}  // namespace sgnlf::harness
