// results/tables/plan.json: the human intent behind the plan of the committed tables
// (tables_plan.hpp derives the rest from the tables themselves). What no results file can say:
// which cells are being run now and by whom, which rerun certified a row (issue 65 item 4), the
// cells not planned and why, the order in which to run what is missing, and which folders hold
// the tables (`roots`). Read strictly: unknown keys and wrong types are errors naming the file and
// the field. Not harness/plan.hpp (a bench run's TablePlan of indexed cells).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/config_fwd.hpp"

namespace sgnlf::harness {

// Rows to run before the rows of later groups ("what to run next"), and why.
struct PlanRowGroup {
  std::vector<std::string> rows;
  std::string why;
};

// Cells no one means to run. An empty list selects every table / row / sequence / plan seed.
struct PlanExclusion {
  std::vector<std::string> tables, rows, sequences;
  std::vector<uint64_t> seeds;
  std::string reason;
};

// One cell: a table's row × sequence × seed.
struct PlanCellRef {
  std::string table, row, sequence;
  uint64_t seed = 1;
};

// A cell being run now (`by`, `since`: free text, e.g. "session 12", "2026-12-06 14:00 UTC").
struct PlanRunning {
  PlanCellRef cell;
  std::string by, since;
};

// A row's certification: `cell` rerun at `commit` gave the same bits as the committed cell.
struct PlanCertification {
  PlanCellRef cell;
  std::string commit, how;
};

struct TablesPlanFile {
  std::string scale = "quick";
  std::vector<uint64_t> seeds{1};
  // Folders of <table>/<scale>/results.json, relative to plan.json's folder; a cell (row ×
  // sequence × seed) is looked up in each in turn, the first holding it wins. The committed
  // tables hold every seed (sgnlf merge makes several-seed tables), so plan.json names ".".
  std::vector<std::string> roots{"."};
  // The PoCL CPU target the cells should share (pocl_cpu_target); "" marks none.
  std::string reference_target;
  std::vector<PlanRowGroup> order;
  std::vector<PlanExclusion> not_planned;
  std::vector<PlanRunning> running;
  std::vector<PlanCertification> certified;
};

// ConfigError naming `where` (the file) and the field, e.g. "plan.json: running[0]: unknown
// key(s) 'sequnce'". Checks the form only; names are checked by plan_file_name_problems.
TablesPlanFile parse_tables_plan_file(const Json& j, const std::string& where);
TablesPlanFile load_tables_plan_file(const std::string& path);

// Every table, row, sequence and seed the file names that this build's table definitions
// (sgnlf bench --list) or the plan's seeds lack, one message each naming `where` and the field.
std::vector<std::string> plan_file_name_problems(const TablesPlanFile& f, const std::string& where);

}  // namespace sgnlf::harness
