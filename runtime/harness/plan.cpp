#include "harness/plan.hpp"

#include <algorithm>
#include <iterator>

#include "core/config.hpp"
#include "harness/results.hpp"

namespace sgnlf::harness {

TablePlan plan_table(const BenchOptions& opt, const BenchHooks& hooks) {
  opt.validate();
  TablePlan p;
  p.table = table_def(opt.table);
  p.sequences = table_sequences(p.table, opt.scale, !opt.data_root.empty());
  if (!opt.sequences.empty())
    p.sequences.erase(std::remove_if(p.sequences.begin(), p.sequences.end(),
                                     [&](const SequenceDef& d) {
                                       return std::find(opt.sequences.begin(),
                                                        opt.sequences.end(),
                                                        d.name) == opt.sequences.end();
                                     }),
                      p.sequences.end());
  p.seeds = opt.seed_list();
  for (const auto& row : p.table.rows) {
    const bool selected = opt.rows.empty() ||
                          std::find(opt.rows.begin(), opt.rows.end(), row.method) != opt.rows.end();
    const bool impl = hooks.implemented && hooks.implemented(row.method);
    p.row_state.push_back(!selected ? "skipped" : impl ? "run" : "not_implemented");
    if (p.row_state.back() != "run") continue;
    for (const auto& sd : p.sequences)
      for (const uint64_t seed : p.seeds)
        p.cells.push_back(Cell{p.cells.size(), row.method, sd.name, seed});
  }
  return p;
}

Json TablePlan::to_json() const {
  Json rows = Json::array(), seqs = Json::array();
  for (size_t i = 0; i < table.rows.size(); ++i)
    rows.push_back(Json{{"method", table.rows[i].method}, {"state", row_state[i]}});
  for (const auto& sd : sequences) seqs.push_back(sd.to_json());
  return Json{{"table", table.name}, {"rows", rows},   {"sequences", seqs},
              {"seeds", seeds},      {"cells", cells.size()}};
}

std::string TablePlan::hash() const { return config_hash(to_json()); }

Json CellOutcome::to_json() const {
  return Json{{"status", status},   {"error", error.empty() ? Json(nullptr) : Json(error)},
              {"data_path", data_path.empty() ? Json(nullptr) : Json(data_path)},
              {"entry", entry},     {"dataset", dataset},
              {"prepare_s", prepare_s >= 0 ? Json(prepare_s) : Json(nullptr)}};
}

CellOutcome CellOutcome::from_json(const Json& j, const std::string& where) {
  const auto bad = [&](const std::string& field, const std::string& what) {
    return ConfigError(where + ": outcome." + field + " " + what);
  };
  if (!j.is_object()) throw ConfigError(where + ": outcome is not an object");
  CellOutcome o;
  o.present = true;
  if (!j.contains("status") || !j["status"].is_string()) throw bad("status", "is missing");
  o.status = j["status"].get<std::string>();
  static const char* known[] = {"ok", "failed", "not_implemented", "missing", "unloadable"};
  if (std::find_if(std::begin(known), std::end(known),
                   [&](const char* k) { return o.status == k; }) == std::end(known))
    throw bad("status", "'" + o.status + "' is not ok|failed|not_implemented|missing|unloadable");
  const auto opt_str = [&](const char* k) {
    if (!j.contains(k) || j[k].is_null()) return std::string();
    if (!j[k].is_string()) throw bad(k, "is not a string");
    return j[k].get<std::string>();
  };
  o.error = opt_str("error");
  o.data_path = opt_str("data_path");
  o.entry = j.value("entry", Json());
  o.dataset = j.value("dataset", Json());
  if (o.status == "ok" && (!o.entry.is_object() || !o.entry.contains("sequence") ||
                           !o.entry.contains("metrics")))
    throw bad("entry", "of an ok cell is not a run entry (sequence, metrics, ...)");
  if (j.contains("prepare_s") && j["prepare_s"].is_number()) o.prepare_s = j["prepare_s"];
  return o;
}

}  // namespace sgnlf::harness
