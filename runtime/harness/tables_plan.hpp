// The plan of the committed tables (issue 65 item 1): every cell (table × row of
// `sgnlf bench --list` × sequence of the plan's scale × seed of plan.json) with its state,
// derived from the committed results.json files and the intent recorded in plan.json
// (tables_plan_file.hpp). A cell is
//   done             committed, at the config hash its method's preset resolves to today
//                    (BenchHooks::config_hash, as `sgnlf merge` flags stale runs)
//   stale            committed at another config hash
//   running          plan.json says someone runs it now (and it is not done)
//   to run           none of these
//   not implemented  this build lacks the method
//   not planned      plan.json excludes it, with the reason
// Each committed cell carries its provenance (the source of its run: commit, binary, device),
// config hash and training time. tables_plan_page.hpp renders it as PLAN.md.
#pragma once
#include <string>
#include <vector>

#include "harness/hooks.hpp"
#include "harness/tables_plan_file.hpp"

namespace sgnlf::harness {

// The PoCL CPU target of an OpenCL device name: "pthread-skylake-avx512-AMD EPYC" ->
// "skylake-avx512" (PoCL names its CPU device "pthread-<LLVM CPU>-<CPU model>"; the model is
// taken to start at the first "-" followed by an upper-case letter). Other devices: the name.
std::string pocl_cpu_target(const std::string& device);

struct PlannedCell {
  PlanCellRef ref;
  std::string label;   // the row's printed label
  std::string state;   // done | stale | running | to run | not implemented | not planned
  std::string note;    // not planned: the reason; running: by and since
  // A committed cell's run (empty when none).
  bool committed = false;
  std::string results;      // the results.json it is in, relative to the plan's root
  std::string commit;       // the checkout's sha (7), " (dirty)" when it was
  std::string binary;       // the binary's build sha (7) and "clean"/"dirty", "" when unrecorded
  std::string device;       // OpenCL device of the run
  bool other_target = false;  // its PoCL CPU target is not the plan's reference_target
  std::string config_hash;
  std::string current_hash;  // today's for the row ("" when unknown)
  double train_s = -1;       // timings.train (seconds), < 0 when unrecorded
  bool run_files = false;    // <table>/<scale>/runs/<method>/<sequence>/seed<k>/ is committed
  std::string certifies;     // "at COMMIT: HOW" when plan.json says this cell certified its row
};

struct PlannedTable {
  std::string name, title;
  std::vector<PlannedCell> cells;  // row, then sequence, then seed (definition order)
  size_t count(const std::string& state) const;
};

struct TablesPlan {
  std::string scale;
  std::vector<PlannedTable> tables;  // sgnlf bench --list order
  // What plan.json claims that the tables contradict: a running cell that is done, a
  // certified cell that is not done. One message each, naming plan.json's field.
  std::vector<std::string> problems;
};

// Reads <root>/<plan root>/<table>/<scale>/results.json for every table of the definitions
// (a missing file: no committed cells). Throws ConfigError/IoError for an unreadable one.
// `plan_where` names plan.json in problems.
TablesPlan derive_tables_plan(const std::string& root, const TablesPlanFile& f,
                              const BenchHooks& hooks, const std::string& plan_where);

}  // namespace sgnlf::harness
