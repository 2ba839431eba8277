#include "harness/table_check.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/config.hpp"
#include "harness/combine.hpp"
#include "harness/markdown.hpp"
#include "harness/schema.hpp"

namespace sgnlf::harness {
namespace fs = std::filesystem;
namespace {

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : " ") + x;
  return s;
}

void check_rows(const Json& r, const TableDef& def, const BenchHooks& hooks,
                std::vector<std::string>& p) {
  std::vector<std::string> got, want;
  for (const auto& row : r.value("rows", Json::array())) got.push_back(row.value("method", ""));
  for (const auto& d : def.rows) want.push_back(d.method);
  if (got != want) {
    p.push_back("rows are [" + join(got) + "], table " + def.name + " has [" + join(want) +
                "] (sgnlf bench --list)");
    return;
  }
  for (size_t i = 0; i < want.size(); ++i) {
    const Json& row = r["rows"][i];
    const std::string st = row.value("status", "");
    if (row.value("label", "") != def.rows[i].label)
      p.push_back("row " + want[i] + ": label '" + row.value("label", "") + "', the table's is '" +
                  def.rows[i].label + "'");
    if (st == "skipped")
      p.push_back("row " + want[i] + " was left out by --rows (status skipped): a table has every "
                  "row; combine partial runs with sgnlf merge (results/tables/README.md)");
    else if (st != "ok" && st != "failed" && st != "not_implemented" && st != "not_run")
      p.push_back("row " + want[i] + ": unknown status '" + st + "'");
    if (hooks.implemented && (st == "not_implemented") == hooks.implemented(want[i]))
      p.push_back("row " + want[i] + ": status '" + st + "' but this build " +
                  (hooks.implemented(want[i]) ? "implements it (regenerate: sgnlf merge)"
                                              : "does not implement it"));
  }
}

void check_sequences(const Json& r, const std::vector<SequenceDef>& defs,
                     std::vector<std::string>& p) {
  static const char* kDefKeys[] = {"name",     "preset", "frequency", "frames",  "width",
                                   "sequence", "start",  "stride",    "real_dir"};
  std::vector<std::string> got, want;
  std::set<std::string> run;
  for (const auto& s : r.value("sequences", Json::array())) {
    got.push_back(s.value("name", ""));
    run.insert(got.back());
  }
  for (const auto& s : r.value("skipped_sequences", Json::array())) got.push_back(s.value("name", ""));
  for (const auto& d : defs) want.push_back(d.name);
  std::vector<std::string> gs = got, ws = want;
  std::sort(gs.begin(), gs.end());
  std::sort(ws.begin(), ws.end());
  if (gs != ws)
    p.push_back("sequences (run and skipped) are [" + join(got) + "], the scale has [" +
                join(want) + "] (sgnlf bench --list)");
  for (const auto& s : r.value("sequences", Json::array())) {
    const auto it = std::find_if(defs.begin(), defs.end(),
                                 [&](const SequenceDef& d) { return d.name == s.value("name", ""); });
    if (it == defs.end()) continue;
    const Json d = it->to_json();
    for (const char* k : kDefKeys)
      if (d.contains(k) != s.contains(k) || (d.contains(k) && d[k] != s[k]))
        p.push_back("sequence " + it->name + ": " + k + " is " +
                    (s.contains(k) ? s[k].dump() : "absent") + ", the definition's " +
                    (d.contains(k) ? d[k].dump() : "absent"));
  }
  for (const auto& row : r.value("rows", Json::array()))
    for (const auto& e : row.value("sequences", Json::array()))
      if (!run.count(e.value("sequence", "")))
        p.push_back("row " + row.value("method", "") + " has a run of " +
                    e.value("sequence", "") + ", which is not in sequences[]");
}

// A combined table's per-row bookkeeping as this build computes it.
void check_combined(const Json& r, const std::vector<SequenceDef>& defs, const BenchHooks& hooks,
                    std::vector<std::string>& p) {
  const std::string scale = r.value("scale", "");
  for (const auto& row : r.value("rows", Json::array())) {
    const std::string m = row.value("method", "");
    const std::string cur = hooks.config_hash ? hooks.config_hash(m, scale) : "";
    const Json want_cur = cur.empty() ? Json(nullptr) : Json(cur);
    const std::string fix = " (refresh: sgnlf merge --out DIR DIR/results.json)";
    if (row.value("current_config_hash", Json()) != want_cur)
      p.push_back("row " + m + ": current_config_hash " +
                  row.value("current_config_hash", Json()).dump() + ", this build's " +
                  want_cur.dump() + fix);
    std::set<std::string> ran;
    for (const auto& e : row.value("sequences", Json::array())) {
      ran.insert(e.value("sequence", ""));
      Json stale = nullptr;
      if (!cur.empty()) {
        bool any = false;
        for (const auto& x : e.contains("runs") ? e["runs"] : Json::array({e}))
          any |= x.value("config_hash", Json()) != Json(cur);
        stale = any;
      }
      if (e.value("stale", Json()) != stale)
        p.push_back("row " + m + " / " + e.value("sequence", "") + ": stale is " +
                    e.value("stale", Json()).dump() + ", this build says " + stale.dump() + fix);
    }
    Json not_run = Json::array();
    for (const auto& d : defs)
      if (!ran.count(d.name)) not_run.push_back(d.name);
    if (row.value("sequences_not_run", Json()) != not_run)
      p.push_back("row " + m + ": sequences_not_run is " +
                  row.value("sequences_not_run", Json()).dump() + ", should be " + not_run.dump());
  }
}

}  // namespace

std::string first_difference(const std::string& a, const std::string& b) {
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  for (int n = 1;; ++n) {
    const bool ea = !std::getline(sa, la), eb = !std::getline(sb, lb);
    if (ea && eb) return "";
    if (ea != eb || la != lb)
      return "line " + std::to_string(n) + ": rendered '" + (ea ? "<end>" : la) + "', committed '" +
             (eb ? "<end>" : lb) + "'";
  }
}

std::vector<std::string> check_committed_table(const Json& r, const std::string& markdown,
                                               const std::string& table_dir,
                                               const std::string& scale_dir,
                                               const BenchHooks& hooks) {
  std::vector<std::string> p;
  if (!is_results_table(r) || r.value("schema_version", Json()) != Json(kSchemaVersion))
    return {"results.json is not an " + std::string(kSchemaName) + " v" +
            std::to_string(kSchemaVersion) + " table"};
  const std::string table = r.value("table", ""), scale = r.value("scale", "");
  if (table != table_dir) p.push_back("table '" + table + "' is committed under " + table_dir + "/");
  if (scale != scale_dir) p.push_back("scale '" + scale + "' is committed under " + scale_dir + "/");
  const auto scales = scale_names();
  if (std::find(scales.begin(), scales.end(), scale) == scales.end()) {
    p.push_back("unknown scale '" + scale + "'");
    return p;
  }
  TableDef def;
  try {
    def = table_def(table);
  } catch (const std::exception& e) {
    p.push_back(e.what());
    return p;
  }
  const auto defs = table_sequences(def, scale, r.value("data", "") == "real");
  check_rows(r, def, hooks, p);
  check_sequences(r, defs, p);
  if (r.contains("combined_from")) check_combined(r, defs, hooks, p);
  const std::string rendered = render_markdown(r);
  if (rendered != markdown)
    p.push_back("table.md is not the rendering of results.json (" +
                first_difference(rendered, markdown) + "; re-render: sgnlf check-tables --render)");
  return p;
}

std::vector<std::string> check_committed_tables(const std::string& root, const BenchHooks& hooks,
                                                size_t* tables_found) {
  std::vector<std::string> p;
  size_t n = 0;
  if (!fs::is_directory(root)) return {root + " is not a folder"};
  std::vector<fs::path> tables;
  for (const auto& e : fs::directory_iterator(root))
    if (e.is_directory()) tables.push_back(e.path());
  std::sort(tables.begin(), tables.end());
  for (const auto& t : tables) {
    std::vector<fs::path> scales;
    for (const auto& e : fs::directory_iterator(t))
      if (e.is_directory()) scales.push_back(e.path());
    std::sort(scales.begin(), scales.end());
    if (scales.empty()) p.push_back(t.string() + ": no <scale>/ folder");
    for (const auto& s : scales) {
      const std::string where = (t.filename() / s.filename()).string() + ": ";
      const fs::path json = s / "results.json", md = s / "table.md";
      if (!fs::is_regular_file(json) || !fs::is_regular_file(md)) {
        p.push_back(where + "results.json or table.md is missing");
        continue;
      }
      Json r;
      try {
        r = load_json_file(json.string());
      } catch (const std::exception& e) {
        p.push_back(where + e.what());
        continue;
      }
      std::ifstream f(md, std::ios::binary);
      const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
      ++n;
      for (const auto& q : check_committed_table(r, text, t.filename().string(),
                                                 s.filename().string(), hooks))
        p.push_back(where + q);
    }
  }
  if (tables_found) *tables_found = n;
  return p;
}

}  // namespace sgnlf::harness
