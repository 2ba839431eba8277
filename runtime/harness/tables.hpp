// Table definitions as data: which rows (methods), sequences per scale, and metric columns
// each table has (runtime/harness/tables.json), and the paper's numbers beside them
// (results/paper_tables.json, protocol §5). Both files are embedded at configure time.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "core/config_fwd.hpp"

namespace sgnlf::harness {

const std::string& tables_json();        // embedded runtime/harness/tables.json
const std::string& paper_tables_json();  // embedded results/paper_tables.json

// A metric's direction: "lower" or "higher" is better, or "none" for a diagnostic that is
// reported and compared but never a regression (opacity_mean, mix_median_fraction). A part of
// a metric (`part_of`: CD's two directions, a variant such as median_cd) takes the direction
// of the metric it belongs to when it names none, and its loose tolerance when tables.json has
// none of its own (metric_tolerance).
struct MetricInfo {
  std::string key, label, unit;
  std::string better = "lower";  // lower | higher | none
  bool lower_better = true;      // better == "lower"
  std::string part_of;           // "" = a metric of its own
  int digits = 4;
  bool judged() const { return better != "none"; }
  // " ↓" (lower is better), " ↑" (higher), "" (a diagnostic): for column headers.
  const char* arrow() const { return better == "lower" ? " ↓" : better == "higher" ? " ↑" : ""; }
};

struct RowDef {
  std::string method;  // pipeline method name (MethodRequest::method)
  std::string label;   // as printed in the table
};

// One sequence of a table. Synthetic twins: `name` is a named sequence of the simulator,
// `frames`/`width` (0 = the sequence's own) shrink it for the smoke scale. Real data: the
// source sequence, first frame, frame count and stride in the dataset's own layout.
// A real sequence inside a synthetic scale sets `real_dir`: a folder under the real-data root
// (BenchOptions::real_root) holding the dataset in its own layout; the window is chosen by
// sequence/start/frames/stride as under --data-root. It runs only when that folder exists
// and is averaged apart from the twins (results/schema.md).
// `test_frames` (positions in the window, 0 = its first frame) replace the sequence's split,
// e.g. LiDAR4D's dynamic windows (10, 20, 30, 40 of 51) read with --data-root; a twin's own
// split comes from its named sequence (datasets/sequences.json) and needs none.
struct SequenceDef {
  std::string name, preset, frequency;
  int frames = 0, width = 0;
  std::string sequence;
  int start = -1, stride = 0;
  std::vector<int> test_frames;
  std::string real_dir;  // "" = a synthetic twin (or a --data-root window)
  bool is_real_dir() const { return !real_dir.empty(); }
  Json to_json() const;  // keys away from their defaults only (real_dir only when set)
};

// Parses one sequence of tables.json (unknown keys and wrong types rejected); `where` names it
// in errors. `real_dir` must be a non-empty relative path without "..".
SequenceDef parse_sequence_def(const Json& j, const std::string& where);

struct TableDef {
  std::string name, title;
  std::vector<RowDef> rows;
  std::vector<std::string> columns;        // the paper's columns (ours beside theirs)
  std::vector<std::string> extra_columns;  // ours only
  std::map<std::string, std::vector<SequenceDef>> scales;  // smoke, quick, paper
  std::vector<SequenceDef> real;           // with --data-root (no real_dir there)
};

std::vector<std::string> table_names();
std::vector<std::string> scale_names();  // smoke, quick, paper
// Throws ConfigError naming the table and listing the known ones.
TableDef table_def(const std::string& name);
// The sequences a run uses: the scale's synthetic twins, or the real windows.
std::vector<SequenceDef> table_sequences(const TableDef& t, const std::string& scale, bool real);

// Metric metadata; nullptr for a metric the table file does not describe. A variant
// "<prefix><m>" of tables.json "metric_variants" (median_cd, mix_fscore, ...) is described
// when <m> is: a part of <m>, with its direction and unit.
const MetricInfo* metric_info(const std::string& key);
// The paper's numbers for one row: {metric: value}; empty object when the paper has none.
Json paper_numbers(const std::string& table, const std::string& method);
// Where a table's paper numbers come from (paper_tables.json "sources"; default: protocol §5).
std::string paper_source(const std::string& table);
// Numbers from third-party notes (protocol §5, "not verified"): {metric: value}.
Json unverified_numbers(const std::string& table, const std::string& method);
// The "tolerances" block of tables.json (documented in results/schema.md).
const Json& tolerance_table();

}  // namespace sgnlf::harness
