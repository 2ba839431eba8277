#include "harness/tables_plan_file.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "core/config.hpp"
#include "harness/tables.hpp"

namespace sgnlf::harness {
namespace {

// The objects of an array field, each read by `read(reader)`; the reader is finished after.
template <typename T, typename F>
std::vector<T> read_list(ConfigReader& parent, const std::string& key, F read) {
  std::vector<T> out;
  Json a = Json::array();
  parent.get(key, a);
  if (!a.is_array())
    throw ConfigError(parent.where() + ": key '" + key + "' must be a list, got " + a.dump());
  for (size_t i = 0; i < a.size(); ++i) {
    ConfigReader r(a[i], parent.where() + ": " + key + "[" + std::to_string(i) + "]");
    out.push_back(read(r));
    r.finish();
  }
  return out;
}

void require_text(const std::string& value, const std::string& key, const ConfigReader& r) {
  if (value.empty()) throw ConfigError(r.where() + ": '" + key + "' must not be empty");
}

PlanCellRef read_cell(ConfigReader& r) {
  PlanCellRef c;
  r.require("table", c.table).require("row", c.row).require("sequence", c.sequence).require("seed", c.seed);
  return c;
}

bool is_commit(const std::string& s) {
  return s.size() >= 7 && s.size() <= 40 &&
         std::all_of(s.begin(), s.end(), [](char ch) { return std::isxdigit(static_cast<unsigned char>(ch)); });
}

std::string cell_text(const PlanCellRef& c) {
  return c.table + " / " + c.row + " / " + c.sequence + " / seed " + std::to_string(c.seed);
}

}  // namespace

TablesPlanFile parse_tables_plan_file(const Json& j, const std::string& where) {
  TablesPlanFile f;
  ConfigReader r(j, where);
  r.get("scale", f.scale).require("seeds", f.seeds).get("roots", f.roots);
  r.get("reference_target", f.reference_target);
  const auto scales = scale_names();
  if (std::find(scales.begin(), scales.end(), f.scale) == scales.end())
    throw ConfigError(where + ": scale '" + f.scale + "' is not a scale of sgnlf bench --list");
  if (f.seeds.empty() || std::set<uint64_t>(f.seeds.begin(), f.seeds.end()).size() != f.seeds.size())
    throw ConfigError(where + ": seeds must be a non-empty list without repeats, got " + Json(f.seeds).dump());
  if (f.roots.empty()) throw ConfigError(where + ": roots must not be empty");
  f.order = read_list<PlanRowGroup>(r, "order", [](ConfigReader& x) {
    PlanRowGroup g;
    x.require("rows", g.rows).require("why", g.why);
    if (g.rows.empty()) throw ConfigError(x.where() + ": 'rows' must not be empty");
    require_text(g.why, "why", x);
    return g;
  });
  f.not_planned = read_list<PlanExclusion>(r, "not_planned", [](ConfigReader& x) {
    PlanExclusion e;
    x.get("tables", e.tables).get("rows", e.rows).get("sequences", e.sequences).get("seeds", e.seeds);
    x.require("reason", e.reason);
    require_text(e.reason, "reason", x);
    return e;
  });
  f.running = read_list<PlanRunning>(r, "running", [](ConfigReader& x) {
    PlanRunning p;
    p.cell = read_cell(x);
    x.require("by", p.by).require("since", p.since);
    require_text(p.by, "by", x);
    return p;
  });
  f.certified = read_list<PlanCertification>(r, "certified", [](ConfigReader& x) {
    PlanCertification c;
    c.cell = read_cell(x);
    x.require("commit", c.commit).require("how", c.how);
    if (!is_commit(c.commit))
      throw ConfigError(x.where() + ": 'commit' must be 7 to 40 hex digits, got '" + c.commit + "'");
    require_text(c.how, "how", x);
    return c;
  });
  r.finish();
  std::set<std::pair<std::string, std::string>> rows_certified;
  for (size_t i = 0; i < f.certified.size(); ++i)
    if (!rows_certified.insert({f.certified[i].cell.table, f.certified[i].cell.row}).second)
      throw ConfigError(where + ": certified[" + std::to_string(i) + "]: row " +
                        f.certified[i].cell.table + " / " + f.certified[i].cell.row +
                        " is certified twice (one cell per row)");
  for (size_t i = 0; i < f.running.size(); ++i)
    for (size_t k = 0; k < i; ++k)
      if (cell_text(f.running[k].cell) == cell_text(f.running[i].cell))
        throw ConfigError(where + ": running[" + std::to_string(i) + "]: " +
                          cell_text(f.running[i].cell) + " is also running[" + std::to_string(k) + "]");
  return f;
}

TablesPlanFile load_tables_plan_file(const std::string& path) {
  return parse_tables_plan_file(load_json_file(path), path);
}

std::vector<std::string> plan_file_name_problems(const TablesPlanFile& f, const std::string& where) {
  std::vector<std::string> p;
  const auto tables = table_names();
  const auto has = [](const std::vector<std::string>& v, const std::string& x) {
    return std::find(v.begin(), v.end(), x) != v.end();
  };
  const auto rows_of = [](const std::string& t) {
    std::vector<std::string> v;
    for (const auto& r : table_def(t).rows) v.push_back(r.method);
    return v;
  };
  const auto sequences_of = [&](const std::string& t) {
    std::vector<std::string> v;
    for (const auto& s : table_sequences(table_def(t), f.scale, false)) v.push_back(s.name);
    return v;
  };
  const auto check_seed = [&](uint64_t s, const std::string& field) {
    if (std::find(f.seeds.begin(), f.seeds.end(), s) == f.seeds.end())
      p.push_back(where + ": " + field + ": seed " + std::to_string(s) + " is not one of the plan's seeds " +
                  Json(f.seeds).dump());
  };
  const auto check_cell = [&](const PlanCellRef& c, const std::string& field) {
    if (!has(tables, c.table)) {
      p.push_back(where + ": " + field + ".table: '" + c.table + "' is not a table of sgnlf bench --list");
      return;
    }
    if (!has(rows_of(c.table), c.row))
      p.push_back(where + ": " + field + ".row: '" + c.row + "' is not a row of table " + c.table);
    if (!has(sequences_of(c.table), c.sequence))
      p.push_back(where + ": " + field + ".sequence: '" + c.sequence + "' is not a sequence of table " +
                  c.table + " at scale " + f.scale);
    check_seed(c.seed, field + ".seed");
  };
  for (size_t i = 0; i < f.running.size(); ++i) check_cell(f.running[i].cell, "running[" + std::to_string(i) + "]");
  for (size_t i = 0; i < f.certified.size(); ++i)
    check_cell(f.certified[i].cell, "certified[" + std::to_string(i) + "]");
  std::set<std::string> all_rows;
  for (const auto& t : tables)
    for (const auto& r : rows_of(t)) all_rows.insert(r);
  for (size_t i = 0; i < f.order.size(); ++i)
    for (const auto& r : f.order[i].rows)
      if (!all_rows.count(r))
        p.push_back(where + ": order[" + std::to_string(i) + "].rows: '" + r + "' is not a row of any table");
  for (size_t i = 0; i < f.not_planned.size(); ++i) {
    const PlanExclusion& e = f.not_planned[i];
    const std::string field = "not_planned[" + std::to_string(i) + "]";
    std::vector<std::string> sel;
    for (const auto& t : e.tables)
      if (has(tables, t)) sel.push_back(t);
      else p.push_back(where + ": " + field + ".tables: '" + t + "' is not a table of sgnlf bench --list");
    if (e.tables.empty()) sel = tables;
    std::set<std::string> rows, seqs;
    for (const auto& t : sel) {
      for (const auto& r : rows_of(t)) rows.insert(r);
      for (const auto& s : sequences_of(t)) seqs.insert(s);
    }
    for (const auto& r : e.rows)
      if (!rows.count(r)) p.push_back(where + ": " + field + ".rows: '" + r + "' is not a row of the tables it names");
    for (const auto& s : e.sequences)
      if (!seqs.count(s))
        p.push_back(where + ": " + field + ".sequences: '" + s + "' is not a sequence of the tables it names");
    for (uint64_t s : e.seeds) check_seed(s, field + ".seeds");
  }
  return p;
}

}  // namespace sgnlf::harness
