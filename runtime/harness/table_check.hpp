// The committed tables (results/tables/<table>/<scale>/{results.json,table.md}) checked against
// this build: every row of the table definition (`sgnlf bench --list`) in order with its label,
// "not implemented" exactly where this build lacks the method, every sequence of the scale
// (run, or in skipped_sequences) with its current definition, a combined table's "stale" flags
// and "not run" lists as this build computes them, and table.md equal to the rendering of
// results.json. `sgnlf check-tables` and the ctest harness_committed_tables run it.
#pragma once
#include <string>
#include <vector>

#include "harness/runner.hpp"

namespace sgnlf::harness {

// The first line where a rendering and a committed text differ ("line N: rendered '...',
// committed '...'"), "" when they are equal: the message of a generated file edited by hand.
std::string first_difference(const std::string& rendered, const std::string& committed);

// Problems of one committed table (empty = fine). `table_dir` / `scale_dir` are the folder
// names it is committed under; `markdown` the committed table.md. Uses hooks.implemented and
// hooks.config_hash when set.
std::vector<std::string> check_committed_table(const Json& results, const std::string& markdown,
                                               const std::string& table_dir,
                                               const std::string& scale_dir,
                                               const BenchHooks& hooks);

// Every <root>/<table>/<scale>/ folder checked (results.json and table.md must be there; other
// files are allowed); problems prefixed with the folder. `tables_found` counts the tables read.
std::vector<std::string> check_committed_tables(const std::string& root, const BenchHooks& hooks,
                                                size_t* tables_found = nullptr);

}  // namespace sgnlf::harness
