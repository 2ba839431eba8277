// A table run's plan (rows × sequences × seeds as indexed cells) and one cell's outcome.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "harness/hooks.hpp"
#include "harness/tables.hpp"

namespace sgnlf::harness {

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

}  // namespace sgnlf::harness
