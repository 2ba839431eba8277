#include "harness/tables_plan_page.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <tuple>

#include "core/config.hpp"
#include "harness/table_check.hpp"

namespace sgnlf::harness {
namespace fs = std::filesystem;
namespace {

const char* const kStates[] = {"done", "stale", "running", "to run", "not planned", "not implemented"};

std::string seeds_text(const std::vector<uint64_t>& seeds) {
  std::string s;
  for (uint64_t x : seeds) s += (s.empty() ? "" : ", ") + std::to_string(x);
  return s;
}

std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

// Which plan.json exclusion a not-planned cell came from (its reason), numbered from 1.
size_t reason_number(const TablesPlanFile& f, const std::string& reason) {
  for (size_t i = 0; i < f.not_planned.size(); ++i)
    if (f.not_planned[i].reason == reason) return i + 1;
  return 0;
}

std::string cell_row(const PlannedCell& c, const TablesPlanFile& f) {
  std::ostringstream o;
  std::string state = c.state == "done" || c.state == "stale" ? "**" + c.state + "**" : c.state;
  if (c.state == "not planned") state += " [" + std::to_string(reason_number(f, c.note)) + "]";
  std::string note = c.state == "running" ? c.note : "";
  if (!c.certifies.empty()) note += (note.empty() ? "" : "; ") + std::string("certifies its row ") + c.certifies;
  o << "| " << c.label << " | " << c.ref.sequence << " | " << c.ref.seed << " | " << state << " | ";
  if (c.committed) {
    std::string hash = "`" + c.config_hash + "`";
    if (c.state == "stale") hash += " (today `" + c.current_hash + "`)";
    o << c.commit << " | " << (c.binary.empty() ? "—" : c.binary) << " | " << c.device
      << (c.other_target ? " (**other target**)" : "") << " | " << hash << " | "
      << (c.train_s >= 0 ? std::to_string(std::lround(c.train_s)) : "—") << " | "
      << (c.run_files ? "yes" : "no");
  } else {
    o << "— | — | — | — | — | —";
  }
  o << " | " << note << " |\n";
  return o.str();
}

// The group of plan.json's order a row is in; rows in none come after every group.
size_t group_of(const TablesPlanFile& f, const std::string& row) {
  for (size_t i = 0; i < f.order.size(); ++i)
    if (std::count(f.order[i].rows.begin(), f.order[i].rows.end(), row)) return i;
  return f.order.size();
}

// The cells to run next (stale or to run), in plan.json's order: the group of their row
// (rows in no group last), then seed, table, row, sequence as the definitions order them.
std::vector<const PlannedCell*> next_cells(const TablesPlan& p, const TablesPlanFile& f) {
  std::vector<std::tuple<size_t, uint64_t, size_t, size_t, const PlannedCell*>> v;
  for (size_t t = 0; t < p.tables.size(); ++t)
    for (size_t k = 0; k < p.tables[t].cells.size(); ++k) {
      const PlannedCell& c = p.tables[t].cells[k];
      if (c.state != "to run" && c.state != "stale") continue;
      v.emplace_back(group_of(f, c.ref.row), c.ref.seed, t, k, &c);
    }
  std::sort(v.begin(), v.end());
  std::vector<const PlannedCell*> out;
  for (const auto& x : v) out.push_back(std::get<4>(x));
  return out;
}

}  // namespace

std::string plan_json_path(const std::string& root) { return (fs::path(root) / "plan.json").string(); }
std::string plan_page_path(const std::string& root) { return (fs::path(root) / "PLAN.md").string(); }

std::string render_tables_plan(const TablesPlan& p, const TablesPlanFile& f) {
  std::ostringstream o;
  o << "# The plan of the committed " << p.scale << " tables\n\n"
    << "<!-- made by `sgnlf check-tables --render` from the committed tables and plan.json; do not "
       "edit -->\n\n"
    << "Every cell (row of `sgnlf bench --list` × sequence × seed " << seeds_text(f.seeds)
    << ") of every " << p.scale << " table. **done**: committed at the config hash its preset "
    << "resolves to today; **stale**: committed at another; running, not planned, and plan.json's "
    << "other intent are kept by hand in `plan.json` (results/tables/README.md). `sgnlf "
    << "check-tables` fails when this page is not the rendering of both.";
  if (!f.reference_target.empty())
    o << " Reference PoCL CPU target: `" << f.reference_target << "`; a cell made on another is "
      << "marked \"other target\".";
  o << "\n\n| table | done | stale | running | to run | not planned | not implemented | cells |\n"
    << "|---|---:|---:|---:|---:|---:|---:|---:|\n";
  std::vector<size_t> total(std::size(kStates), 0);
  size_t all = 0;
  for (const auto& t : p.tables) {
    o << "| [" << t.name << "](#" << t.name << ") ";
    for (size_t i = 0; i < std::size(kStates); ++i) {
      o << "| " << t.count(kStates[i]) << " ";
      total[i] += t.count(kStates[i]);
    }
    o << "| " << t.cells.size() << " |\n";
    all += t.cells.size();
  }
  o << "| all ";
  for (size_t x : total) o << "| " << x << " ";
  o << "| " << all << " |\n";

  o << "\n## What to run next\n\nStale and missing cells, in plan.json's order (`order`: the rows "
       "of an earlier group first), then by seed. Each is `sgnlf bench --table T --scale "
    << p.scale << " --rows ROW --sequences SEQ --seed K --out DIR` (or its `--cells` / `--cell "
       "K`), merged with `sgnlf merge --later-wins --keep-run-files --out results/tables/T/"
    << p.scale << " results/tables/T/" << p.scale << "/results.json DIR/results.json`.\n";
  size_t n = 0, group = size_t(-1);
  for (const PlannedCell* c : next_cells(p, f)) {
    const size_t g = group_of(f, c->ref.row);
    if (g != group) {
      group = g;
      o << "\n" << (g < f.order.size() ? "**" + join(f.order[g].rows, ", ") + "**: " + f.order[g].why
                                       : std::string("**Rows in no group of plan.json's order**"))
        << "\n\n";
    }
    o << ++n << ". " << c->ref.table << " · " << c->label << " (`" << c->ref.row << "`) · "
      << c->ref.sequence << " · seed " << c->ref.seed << " — " << c->state << "\n";
  }
  if (n == 0) o << "\nNothing: every planned cell is done or running.\n";
  std::vector<const PlannedCell*> running;
  for (const auto& t : p.tables)
    for (const auto& c : t.cells)
      if (c.state == "running") running.push_back(&c);
  if (!running.empty()) {
    o << "\nRunning now:\n\n";
    for (const PlannedCell* c : running)
      o << "- " << c->ref.table << " · " << c->label << " · " << c->ref.sequence << " · seed "
        << c->ref.seed << ", " << c->note << "\n";
  }
  if (!f.not_planned.empty()) {
    o << "\n## Not planned\n\n";
    for (size_t i = 0; i < f.not_planned.size(); ++i) o << "[" << i + 1 << "] " << f.not_planned[i].reason << "\n\n";
  }

  for (const auto& t : p.tables) {
    o << "\n## " << t.name << "\n\n" << t.title << ": " << t.cells.size() << " cells, ";
    std::vector<std::string> parts;
    for (const char* s : kStates)
      if (t.count(s)) parts.push_back(std::to_string(t.count(s)) + " " + s);
    o << join(parts, ", ") << ".\n\n"
      << "| row | sequence | seed | state | commit | binary | device | config hash | train (s) | run files | note |\n"
      << "|---|---|---:|---|---|---|---|---|---:|---|---|\n";
    for (const auto& c : t.cells) o << cell_row(c, f);
  }
  return o.str();
}

std::string render_plan_page(const std::string& root, const BenchHooks& hooks) {
  const std::string where = plan_json_path(root);
  const TablesPlanFile f = load_tables_plan_file(where);
  return render_tables_plan(derive_tables_plan(root, f, hooks, where), f);
}

std::vector<std::string> check_tables_plan(const std::string& root, const BenchHooks& hooks) {
  const std::string where = plan_json_path(root), page = plan_page_path(root);
  if (!fs::is_regular_file(where))
    return {where + " is missing: the plan's intent (results/tables/README.md, \"The plan\")"};
  std::vector<std::string> p;
  std::string rendered;
  try {
    const TablesPlanFile f = load_tables_plan_file(where);
    p = plan_file_name_problems(f, where);
    const TablesPlan plan = derive_tables_plan(root, f, hooks, where);
    p.insert(p.end(), plan.problems.begin(), plan.problems.end());
    rendered = render_tables_plan(plan, f);
  } catch (const std::exception& e) {
    p.push_back(e.what());
    return p;
  }
  std::ifstream in(page, std::ios::binary);
  if (!in) {
    p.push_back(page + " is missing (sgnlf check-tables --render)");
    return p;
  }
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text != rendered)
    p.push_back(page + " is not the rendering of the tables and plan.json (" +
                first_difference(rendered, text) + "; re-render: sgnlf check-tables --render)");
  return p;
}

}  // namespace sgnlf::harness
