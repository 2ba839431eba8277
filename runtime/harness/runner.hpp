// The table runner behind `sgnlf bench`: every row (method) of a table on every sequence of
// the chosen scale, with fixed seeds, producing the results JSON of results/schema.md.
// Training and data are injected (BenchHooks), so the runner is testable without them; the
// app passes default_hooks() (wiring.hpp), which calls pipeline::run_method.
#pragma once
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "harness/assemble.hpp"
#include "harness/bench_options.hpp"
#include "harness/hooks.hpp"
#include "harness/plan.hpp"

namespace sgnlf::harness {

// Runs one cell: prepares its sequence (unless `cache` has it) and trains + evaluates; the
// run folder's summary.json records `context` (the bench's context block) as where it ran.
// Failures are recorded in the outcome, not thrown.
CellOutcome execute_cell(const BenchOptions& opt, const BenchHooks& hooks, const TablePlan& plan,
                         const Cell& cell, std::map<std::string, PreparedSequence>& cache,
                         const Json& context);

// Runs the table; `context` is the context block (context_block() + roofline), copied into
// the result. Failures of single runs are recorded in their row (status "failed") and the
// table goes on. A real sequence of a synthetic scale whose folder is missing is skipped with
// a warning and listed in `skipped_sequences` (ConfigError when --sequences named it or no
// sequence is left). Writes nothing itself; see write_outputs().
Json run_table(const BenchOptions& opt, const BenchHooks& hooks, Json context);

// Writes <out>/results.json and <out>/table.md; returns their paths.
std::pair<std::string, std::string> write_outputs(const Json& results, const std::string& out_dir);

}  // namespace sgnlf::harness
