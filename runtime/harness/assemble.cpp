#include "harness/assemble.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "core/config.hpp"
#include "harness/clock.hpp"
#include "harness/results.hpp"
#include "harness/schema.hpp"
#include "harness/stats.hpp"

namespace sgnlf::harness {
namespace fs = std::filesystem;

Json assemble_table(const TablePlan& plan, const std::vector<CellOutcome>& outcomes,
                    const TableHeader& h) {
  require(outcomes.size() == plan.cells.size(), "assemble_table: one outcome per cell");
  const TableDef& t = plan.table;
  const size_t ns = plan.sequences.size(), nk = plan.seeds.size();
  // Cells of row r (its position among the rows that run), sequence s, seed k.
  const auto cell_of = [&](size_t run_row, size_t s, size_t k) -> const CellOutcome& {
    return outcomes[(run_row * ns + s) * nk + k];
  };
  // Real sequences whose folder is missing: found by any cell, skipped up front.
  Json skipped = Json::array();
  std::set<std::string> dropped;  // missing or unloadable
  std::vector<std::string> real_names;
  bool any_real_dir = false;
  for (size_t s = 0; s < ns; ++s) {
    const SequenceDef& sd = plan.sequences[s];
    if (h.real || !sd.is_real_dir()) continue;
    any_real_dir = true;
    const CellOutcome* miss = nullptr;
    for (size_t c = 0; c < plan.cells.size(); ++c)
      if (plan.cells[c].sequence == sd.name && outcomes[c].present &&
          outcomes[c].status == "missing") {
        miss = &outcomes[c];
        break;
      }
    if (miss) {
      skipped.push_back(Json{{"name", sd.name}, {"real_dir", sd.real_dir},
                             {"path", miss->data_path}, {"reason", miss->error}});
      dropped.insert(sd.name);
    } else {
      real_names.push_back(sd.name);
    }
  }
  if (dropped.size() == ns)
    throw ConfigError("bench: table " + t.name + " at scale " + h.config.value("scale", "") +
                      ": no sequence left to run (the real data of every chosen one is missing)");
  std::map<std::string, Json> prepared;
  std::vector<double> prepare_s;
  Json runs = Json::array(), rows = Json::array();
  size_t run_row = 0;
  for (size_t ri = 0; ri < t.rows.size(); ++ri) {
    const RowDef& row = t.rows[ri];
    const std::string& state = plan.row_state[ri];
    if (state != "run") {
      rows.push_back(make_row(t.name, row, state, {}));
      continue;
    }
    std::vector<Json> entries;
    std::string status = "ok", error;
    for (size_t s = 0; s < ns && status == "ok"; ++s) {
      const std::string& name = plan.sequences[s].name;
      for (size_t k = 0; k < nk && status == "ok" && !dropped.count(name); ++k) {
        const CellOutcome& o = cell_of(run_row, s, k);
        require(o.present, "assemble_table: cell " + row.method + " / " + name + " / seed " +
                               std::to_string(plan.seeds[k]) + " has no outcome");
        if (!o.dataset.is_null() && !prepared.count(name)) prepared[name] = o.dataset;
        if (o.prepare_s >= 0) prepare_s.push_back(o.prepare_s);
        if (o.status == "unloadable" || o.status == "missing") {
          skipped.push_back(Json{{"name", name}, {"real_dir", plan.sequences[s].real_dir},
                                 {"path", o.data_path}, {"reason", o.error}});
          dropped.insert(name);
          real_names.erase(std::remove(real_names.begin(), real_names.end(), name),
                           real_names.end());
        } else if (o.status == "not_implemented") {
          status = "not_implemented";
        } else if (o.status == "failed") {
          status = "failed";
          error = name + ": " + o.error;
        } else {
          entries.push_back(o.entry);
          runs.push_back(Json{{"method", row.method},
                              {"sequence", name},
                              {"seed", plan.seeds[k]},
                              {"dataset_seed", o.dataset.value("seed", Json(nullptr))}});
        }
      }
    }
    ++run_row;
    rows.push_back(make_row(t.name, row, status, status == "ok" ? entries : std::vector<Json>{},
                            error, real_names));
    if (status == "failed") rows.back()["sequences"] = entries;  // keep what finished
  }

  Json seq_list = Json::array();
  for (const auto& sd : plan.sequences) {
    if (dropped.count(sd.name)) continue;  // listed in skipped_sequences
    Json s = sd.to_json();
    if (!h.real && sd.is_real_dir())
      s["real_path"] = (fs::path(h.real_root) / sd.real_dir).string();
    if (prepared.count(sd.name)) s["dataset"] = prepared[sd.name];
    seq_list.push_back(s);
  }
  Json context = h.context;
  context["peak_rss_kib"] = h.peak_rss_kib;

  Json r;
  r["schema"] = kSchemaName;
  r["schema_version"] = kSchemaVersion;
  r["kind"] = "table";
  r["table"] = t.name;
  r["title"] = t.title;
  r["scale"] = h.config.value("scale", "");
  r["data"] = h.real ? "real" : "synthetic";
  r["created_utc"] = utc_now();
  r["command"] = h.command;
  r["out_dir"] = h.out_dir;
  r["config"] = h.config;
  r["config_hash"] = config_hash(r["config"]);
  r["seeds"] = Json{{"table_seed", plan.seeds.front()}, {"runs", runs}};
  if (nk > 1) r["seeds"]["table_seeds"] = plan.seeds;
  r["context"] = context;
  r["columns"] = t.columns;
  r["extra_columns"] = t.extra_columns;
  r["metric_definitions"] = h.metric_definitions;
  r["sequences"] = seq_list;
  r["skipped_sequences"] = skipped;
  if (any_real_dir) r["real_root"] = h.real_root;
  r["rows"] = rows;
  r["timings"] = Json{{"prepare_s", summarize(prepare_s)}, {"total_s", h.total_s}};
  r["peak_rss_kib"] = h.peak_rss_kib;
  return r;
}

}  // namespace sgnlf::harness
