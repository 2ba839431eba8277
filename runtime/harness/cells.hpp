// Tables that outgrow one machine (results/schema.md "Cells"): a table is a list of
// independent cells (row × sequence × seed, TablePlan in runner.hpp). `sgnlf bench --cells`
// lists them, `--cell K` runs one and writes a cell file (<out>/cell.json), and `sgnlf merge`
// combines the cell files into the table's results.json, equal to the one-process run's
// after comparable_view() (which drops what may differ: times, paths, the run's context).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "harness/runner.hpp"

namespace sgnlf::harness {

constexpr const char* kCellSchemaName = "sgnlf.cell";
constexpr int kCellSchemaVersion = 1;

// "K<TAB>method<TAB>sequence<TAB>seed" per cell, in index order.
std::vector<std::string> cell_lines(const TablePlan& plan);

// Runs cell `index` of the table alone (its sequence prepared under opt.out_dir) and returns
// the cell file's JSON. ConfigError when the index is out of range.
Json run_cell(const BenchOptions& opt, const BenchHooks& hooks, long index, Json context);
// Writes <out_dir>/cell.json; returns its path.
std::string write_cell(const Json& cell, const std::string& out_dir);

// A cell argument of `sgnlf merge`: a cell file, or a folder holding cell.json.
std::string cell_file_path(const std::string& arg);

// Merges cell files ({path, json}) into the table's results. ConfigError naming the files when
// one is not a cell file, when two come from different tables, scales, data, configs, plans,
// commits or OpenCL devices, when an index repeats, and (listing them) when cells are missing.
Json merge_cells(const std::vector<std::pair<std::string, Json>>& cells,
                 const std::string& command, const std::string& out_dir);

// The results with every field that may differ between two runs of the same table removed
// (results/schema.md "Cells": times, the run's context and paths): a merged table and the
// one-process run are equal after it.
Json comparable_view(const Json& results);
// JSON pointers where comparable_view(a) and comparable_view(b) differ (at most `limit`).
std::vector<std::string> table_differences(const Json& a, const Json& b, size_t limit = 20);

}  // namespace sgnlf::harness
