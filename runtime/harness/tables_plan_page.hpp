// PLAN.md, the plan of the committed tables as a page (issue 65 item 1): a summary per table
// (cells done, stale, running, to run, not planned, not implemented), what to run next in
// plan.json's order, then every table's cells with their provenance. Made from <root>/plan.json
// and the committed results by `sgnlf check-tables --render`; `sgnlf check-tables` fails when
// the committed PLAN.md is not that rendering, when plan.json names what the table definitions
// lack, or when the tables contradict it (tables_plan.hpp).
#pragma once
#include <string>
#include <vector>

#include "harness/tables_plan.hpp"

namespace sgnlf::harness {

std::string plan_json_path(const std::string& root);  // <root>/plan.json
std::string plan_page_path(const std::string& root);  // <root>/PLAN.md

std::string render_tables_plan(const TablesPlan& plan, const TablesPlanFile& f);

// PLAN.md as <root>/plan.json and the tables under <root> make it. ConfigError naming
// plan.json (and the field) when it is not a valid plan file.
std::string render_plan_page(const std::string& root, const BenchHooks& hooks);

// Problems of the plan under <root> (empty = fine), each naming its file: plan.json missing,
// invalid, naming a table, row, sequence or seed the definitions lack, contradicted by the
// tables (a running cell done, a certified cell not done); PLAN.md missing or not the rendering.
std::vector<std::string> check_tables_plan(const std::string& root, const BenchHooks& hooks);

}  // namespace sgnlf::harness
