#include "harness/cells.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <map>
#include <set>

#include "core/config.hpp"
#include "core/log.hpp"
#include "harness/clock.hpp"
#include "harness/context.hpp"
#include "harness/results.hpp"
#include "harness/schema.hpp"

namespace sgnlf::harness {
namespace fs = std::filesystem;
namespace {

const Json& at_path(const Json& j, const std::vector<std::string>& path) {
  static const Json null_json;
  const Json* p = &j;
  for (const auto& k : path) {
    if (!p->is_object() || !p->contains(k)) return null_json;
    p = &(*p)[k];
  }
  return *p;
}

std::string cell_name(const Cell& c) {
  return std::to_string(c.index) + " (" + c.method + " / " + c.sequence + " / seed " +
         std::to_string(c.seed) + ")";
}

// The plan a cell file records, rebuilt against this build's table definition.
TablePlan plan_from_json(const Json& pj, const std::string& where) {
  const auto bad = [&](const std::string& what) {
    return ConfigError("merge: " + where + ": plan " + what);
  };
  if (!pj.is_object() || !pj.contains("table") || !pj["table"].is_string() ||
      !pj.contains("rows") || !pj["rows"].is_array() || !pj.contains("sequences") ||
      !pj["sequences"].is_array() || !pj.contains("seeds") || !pj["seeds"].is_array() ||
      pj["seeds"].empty())
    throw bad("is not {table, rows, sequences, seeds, cells}");
  TablePlan p;
  p.table = table_def(pj["table"].get<std::string>());
  if (pj["rows"].size() != p.table.rows.size())
    throw bad("has " + std::to_string(pj["rows"].size()) + " rows, table " + p.table.name +
              " of this build has " + std::to_string(p.table.rows.size()));
  for (size_t i = 0; i < p.table.rows.size(); ++i) {
    const Json& r = pj["rows"][i];
    if (!r.is_object() || r.value("method", "") != p.table.rows[i].method)
      throw bad("row " + std::to_string(i) + " is " + r.dump() + ", this build's is " +
                p.table.rows[i].method);
    const std::string st = r.value("state", "");
    if (st != "run" && st != "skipped" && st != "not_implemented")
      throw bad("row " + p.table.rows[i].method + " state '" + st + "'");
    p.row_state.push_back(st);
  }
  for (size_t i = 0; i < pj["sequences"].size(); ++i)
    p.sequences.push_back(parse_sequence_def(pj["sequences"][i],
                                             where + ": plan.sequences[" + std::to_string(i) + "]"));
  for (const auto& s : pj["seeds"]) {
    if (!s.is_number_unsigned()) throw bad("seed " + s.dump() + " is not an unsigned integer");
    p.seeds.push_back(s.get<uint64_t>());
  }
  for (size_t ri = 0; ri < p.table.rows.size(); ++ri) {
    if (p.row_state[ri] != "run") continue;
    for (const auto& sd : p.sequences)
      for (const uint64_t seed : p.seeds)
        p.cells.push_back(Cell{p.cells.size(), p.table.rows[ri].method, sd.name, seed});
  }
  if (pj.value("cells", Json()) != Json(p.cells.size()))
    throw bad("says " + pj.value("cells", Json()).dump() + " cells, its rows, sequences and seeds make " +
              std::to_string(p.cells.size()));
  return p;
}

// Times, rates and machine paths of one run entry (and of a several-seed entry's runs).
void strip_run(Json& e) {
  if (!e.is_object()) return;
  e.erase("run_dir");
  e.erase("timings");
  if (e.contains("dataset") && e["dataset"].is_object()) e["dataset"].erase("path");
  if (e.contains("extra") && e["extra"].is_object()) {
    std::vector<std::string> drop;
    for (auto it = e["extra"].begin(); it != e["extra"].end(); ++it) {
      const std::string& k = it.key();
      const auto ends = [&](const std::string& suf) {
        return k.size() >= suf.size() && k.compare(k.size() - suf.size(), suf.size(), suf) == 0;
      };
      if (ends("_seconds") || ends("_per_s")) drop.push_back(k);
    }
    for (const auto& k : drop) e["extra"].erase(k);
  }
  if (e.contains("runs") && e["runs"].is_array())
    for (auto& r : e["runs"]) strip_run(r);
}

}  // namespace

std::vector<std::string> cell_lines(const TablePlan& plan) {
  std::vector<std::string> v;
  for (const auto& c : plan.cells)
    v.push_back(std::to_string(c.index) + "\t" + c.method + "\t" + c.sequence + "\t" +
                std::to_string(c.seed));
  return v;
}

Json run_cell(const BenchOptions& opt, const BenchHooks& hooks, long index, Json context) {
  const TablePlan plan = plan_table(opt, hooks);
  if (index < 0 || size_t(index) >= plan.cells.size())
    throw ConfigError("bench: --cell " + std::to_string(index) + ": table " + opt.table +
                      " at scale " + opt.scale + " has " + std::to_string(plan.cells.size()) +
                      " cells (0.." + std::to_string(long(plan.cells.size()) - 1) +
                      ", see --cells)");
  const Cell& c = plan.cells[size_t(index)];
  log::info("[bench] cell ", cell_name(c), " of ", plan.cells.size());
  const double t0 = now_s();
  std::map<std::string, PreparedSequence> cache;
  const CellOutcome o = execute_cell(opt, hooks, plan, c, cache, context);
  if (o.status == "failed") log::warn("[bench] cell ", cell_name(c), " failed: ", o.error);
  if (o.status == "missing" || o.status == "unloadable")
    log::warn("[bench] cell ", cell_name(c), ": sequence skipped: ", o.error);
  context["peak_rss_kib"] = peak_rss_kib();
  Json j;
  j["schema"] = kCellSchemaName;
  j["schema_version"] = kCellSchemaVersion;
  j["kind"] = "cell";
  j["table"] = opt.table;
  j["scale"] = opt.scale;
  j["data"] = opt.data_root.empty() ? "synthetic" : "real";
  j["config"] = opt.to_json();
  j["config_hash"] = config_hash(j["config"]);
  j["plan"] = plan.to_json();
  j["plan_hash"] = plan.hash();
  j["cell"] = Json{{"index", c.index}, {"method", c.method}, {"sequence", c.sequence},
                   {"seed", c.seed}};
  j["outcome"] = o.to_json();
  j["context"] = context;
  j["metric_definitions"] = hooks.metric_definitions ? hooks.metric_definitions() : Json();
  j["real_root"] = opt.resolved_real_root();
  j["command"] = opt.command;
  j["out_dir"] = opt.out_dir;
  j["created_utc"] = utc_now();
  j["total_s"] = now_s() - t0;
  j["peak_rss_kib"] = peak_rss_kib();
  return j;
}

std::string write_cell(const Json& cell, const std::string& out_dir) {
  fs::create_directories(out_dir);
  const std::string path = (fs::path(out_dir) / "cell.json").string();
  write_json_file(path, cell);
  return path;
}

std::string cell_file_path(const std::string& arg) {
  if (fs::is_directory(arg)) {
    const std::string p = (fs::path(arg) / "cell.json").string();
    if (!fs::is_regular_file(p))
      throw ConfigError("merge: " + arg + " is a folder without a cell.json (run sgnlf bench "
                        "--cell K --out " + arg + ")");
    return p;
  }
  if (!fs::is_regular_file(arg)) throw ConfigError("merge: " + arg + ": no such cell file or folder");
  return arg;
}

Json merge_cells(const std::vector<std::pair<std::string, Json>>& cells,
                 const std::string& command, const std::string& out_dir) {
  if (cells.empty()) throw ConfigError("merge: no cell files given");
  // Every file is a cell file of this schema, with the fields merge reads.
  for (const auto& [path, j] : cells) {
    if (!j.is_object() || j.value("schema", Json()) != Json(kCellSchemaName) ||
        j.value("schema_version", Json()) != Json(kCellSchemaVersion))
      throw ConfigError("merge: " + path + " is not a " + std::string(kCellSchemaName) + " v" +
                        std::to_string(kCellSchemaVersion) + " cell file (schema " +
                        (j.is_object() ? j.value("schema", Json()).dump() : j.dump().substr(0, 40)) +
                        "; a results.json is not a cell: make cells with sgnlf bench --cell K)");
    for (const char* k : {"table", "scale", "data", "config_hash", "plan_hash"})
      if (!j.contains(k) || !j[k].is_string())
        throw ConfigError("merge: " + path + ": field '" + k + "' is missing or not a string");
    for (const char* k : {"config", "plan", "cell", "outcome", "context"})
      if (!j.contains(k) || !j[k].is_object())
        throw ConfigError("merge: " + path + ": field '" + k + "' is missing or not an object");
    if (!j["cell"].contains("index") || !j["cell"]["index"].is_number_unsigned())
      throw ConfigError("merge: " + path + ": field 'cell.index' is missing or not an index");
  }
  // One table, one config, one commit, one device.
  const auto& [ref_path, ref] = cells.front();
  const std::vector<std::pair<std::string, std::vector<std::string>>> same = {
      {"table", {"table"}},
      {"scale", {"scale"}},
      {"data", {"data"}},
      {"config (config_hash)", {"config_hash"}},
      {"cell plan (plan_hash: rows, sequences, seeds, implemented methods)", {"plan_hash"}},
      {"commit (context.git.sha)", {"context", "git", "sha"}},
      {"working-tree state (context.git.dirty)", {"context", "git", "dirty"}},
      {"build commit (context.build.git.sha)", {"context", "build", "git", "sha"}},
      {"OpenCL device (context.opencl.device)", {"context", "opencl", "device"}},
      {"OpenCL driver (context.opencl.driver_version)", {"context", "opencl", "driver_version"}},
      {"device profile (context.device_profile)", {"context", "device_profile"}},
  };
  for (const auto& [path, j] : cells)
    for (const auto& [what, key] : same)
      if (at_path(j, key) != at_path(ref, key))
        throw ConfigError("merge: " + ref_path + " and " + path + " are from different " + what +
                          ": " + at_path(ref, key).dump() + " vs " + at_path(j, key).dump());
  const TablePlan plan = plan_from_json(ref["plan"], ref_path);
  if (plan.hash() != ref["plan_hash"].get<std::string>())
    throw ConfigError("merge: " + ref_path + ": plan_hash " + ref["plan_hash"].dump() +
                      " does not match its plan (" + plan.hash() + ")");
  // Each index once, matching the plan's cell.
  std::vector<CellOutcome> outcomes(plan.cells.size());
  std::vector<std::string> file_of(plan.cells.size());
  for (const auto& [path, j] : cells) {
    const uint64_t k = j["cell"]["index"].get<uint64_t>();
    if (k >= plan.cells.size())
      throw ConfigError("merge: " + path + ": cell.index " + std::to_string(k) +
                        " is out of range (the table has " + std::to_string(plan.cells.size()) +
                        " cells)");
    const Cell& c = plan.cells[k];
    if (j["cell"].value("method", "") != c.method || j["cell"].value("sequence", "") != c.sequence ||
        j["cell"].value("seed", Json()) != Json(c.seed))
      throw ConfigError("merge: " + path + ": cell " + j["cell"].dump() +
                        " is not the plan's cell " + cell_name(c));
    if (!file_of[k].empty())
      throw ConfigError("merge: cell " + cell_name(c) + " is given twice: " + file_of[k] +
                        " and " + path);
    file_of[k] = path;
    outcomes[k] = CellOutcome::from_json(j["outcome"], path);
  }
  std::vector<std::string> missing;
  for (const auto& c : plan.cells)
    if (file_of[c.index].empty()) missing.push_back(cell_name(c));
  if (!missing.empty()) {
    std::string list;
    for (size_t i = 0; i < missing.size() && i < 20; ++i) list += (i ? ", " : "") + missing[i];
    if (missing.size() > 20) list += ", and " + std::to_string(missing.size() - 20) + " more";
    throw ConfigError("merge: " + std::to_string(missing.size()) + " of " +
                      std::to_string(plan.cells.size()) + " cells missing: " + list +
                      " (run them with sgnlf bench ... --cell K)");
  }
  // A real sequence is either there for every cell or missing for every cell.
  for (const auto& sd : plan.sequences) {
    std::string there, gone;
    for (const auto& c : plan.cells) {
      if (c.sequence != sd.name) continue;
      (outcomes[c.index].status == "missing" ? gone : there) = file_of[c.index];
    }
    if (!there.empty() && !gone.empty())
      throw ConfigError("merge: sequence " + sd.name + "'s real data was missing for " + gone +
                        " but not for " + there + " (run every cell where the data is)");
  }
  // The lowest index's context and header stand for the table.
  size_t first = 0;
  double total = 0;
  long rss = 0;
  for (size_t i = 0; i < cells.size(); ++i) {
    if (cells[i].second["cell"]["index"] < cells[first].second["cell"]["index"]) first = i;
    total += cells[i].second.value("total_s", 0.0);
    rss = std::max(rss, cells[i].second.value("peak_rss_kib", 0L));
  }
  const Json& head = cells[first].second;
  TableHeader h;
  h.config = head["config"];
  h.command = command;
  h.out_dir = out_dir;
  h.real_root = head.value("real_root", "");
  h.real = head["data"] == "real";
  h.metric_definitions = head.value("metric_definitions", Json());
  h.context = head["context"];
  h.total_s = total;
  h.peak_rss_kib = rss;
  Json r = assemble_table(plan, outcomes, h);
  r["merged_from"] = Json{{"cells", plan.cells.size()}, {"files", file_of}};
  return r;
}

Json comparable_view(const Json& results) {
  Json r = results;
  for (const char* k : {"created_utc", "command", "out_dir", "context", "timings", "peak_rss_kib",
                        "merged_from", "real_root"})
    r.erase(k);
  if (r.contains("sequences") && r["sequences"].is_array())
    for (auto& s : r["sequences"]) {
      s.erase("real_path");
      if (s.contains("dataset") && s["dataset"].is_object()) s["dataset"].erase("path");
    }
  if (r.contains("skipped_sequences") && r["skipped_sequences"].is_array())
    for (auto& s : r["skipped_sequences"]) {
      s.erase("path");
      s.erase("reason");
    }
  if (r.contains("rows") && r["rows"].is_array())
    for (auto& row : r["rows"]) {
      row.erase("timings");
      if (row.contains("sequences") && row["sequences"].is_array())
        for (auto& e : row["sequences"]) strip_run(e);
    }
  return r;
}

std::vector<std::string> table_differences(const Json& a, const Json& b, size_t limit) {
  std::vector<std::string> out;
  const Json patch = Json::diff(comparable_view(a), comparable_view(b));
  for (const auto& op : patch) {
    if (out.size() >= limit) break;
    out.push_back(op.value("path", "") + " (" + op.value("op", "") + ")");
  }
  return out;
}

}  // namespace sgnlf::harness
