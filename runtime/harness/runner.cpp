#include "harness/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <map>
#include <set>

#include "core/log.hpp"
#include "core/progress.hpp"
#include "harness/clock.hpp"
#include "harness/context.hpp"
#include "harness/markdown.hpp"
#include "harness/results.hpp"
#include "harness/schema.hpp"
#include "harness/stats.hpp"

namespace sgnlf::harness {
namespace fs = std::filesystem;

void BenchOptions::validate() const {
  table_def(table);  // throws for an unknown table
  const auto scales = scale_names();
  if (std::find(scales.begin(), scales.end(), scale) == scales.end())
    throw ConfigError("bench: unknown scale '" + scale + "' (known: smoke, quick, paper)");
  if (out_dir.empty()) throw ConfigError("bench: --out is required");
  for (size_t i = 0; i < seeds.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (seeds[i] == seeds[j])
        throw ConfigError("bench: --seeds: seed " + std::to_string(seeds[i]) +
                          " is listed twice");
  if (!data_root.empty() && !fs::is_directory(data_root))
    throw ConfigError("bench: --data-root '" + data_root + "' is not a directory");
  if (!real_root.empty() && !fs::is_directory(real_root))
    throw ConfigError("bench: --real-root '" + real_root + "' is not a directory");
  const TableDef t = table_def(table);
  for (const auto& r : rows) {
    const bool known = std::any_of(t.rows.begin(), t.rows.end(),
                                   [&](const RowDef& d) { return d.method == r; });
    if (!known) throw ConfigError("bench: --rows: table " + table + " has no row '" + r + "'");
  }
  const auto seqs = table_sequences(t, scale, !data_root.empty());
  for (const auto& q : sequences) {
    const bool known = std::any_of(seqs.begin(), seqs.end(),
                                   [&](const SequenceDef& d) { return d.name == q; });
    if (!known)
      throw ConfigError("bench: --sequences: table " + table + " at scale " + scale +
                        " has no sequence '" + q + "'");
    // A real sequence chosen by name must be there: an error, not a silent skip.
    for (const auto& d : seqs)
      if (d.name == q && d.is_real_dir() && data_root.empty() &&
          !fs::is_directory(sequence_data_root(d, *this)))
        throw ConfigError("bench: --sequences " + q + ": real data not found at " +
                          sequence_data_root(d, *this) +
                          " (--real-root DIR, or $SGNLF_SHARED_DIR/data/real)");
  }
}

std::string BenchOptions::resolved_real_root() const {
  return real_root.empty() ? default_real_root() : real_root;
}

std::string default_real_root() {
  const char* env = std::getenv("SGNLF_SHARED_DIR");
  if (env && *env) return (fs::path(env) / "data" / "real").string();
  return (fs::path("..") / "shared" / "data" / "real").string();
}

std::string sequence_data_root(const SequenceDef& s, const BenchOptions& opt) {
  if (!opt.data_root.empty()) return opt.data_root;
  if (s.is_real_dir()) return (fs::path(opt.resolved_real_root()) / s.real_dir).string();
  return "";
}

std::vector<uint64_t> BenchOptions::seed_list() const {
  return seeds.empty() ? std::vector<uint64_t>{seed} : seeds;
}

Json BenchOptions::to_json() const {
  Json j{{"table", table},   {"scale", scale}, {"data_root", data_root},
         {"device", device}, {"seed", seed},   {"roofline", roofline}};
  const auto sl = seed_list();
  if (sl.size() > 1) {  // several seeds: `seeds` instead of `seed` (one seed: unchanged)
    j.erase("seed");
    j["seeds"] = sl;
  } else {
    j["seed"] = sl.front();
  }
  if (!rows.empty()) j["rows"] = rows;
  if (!sequences.empty()) j["sequences"] = sequences;
  return j;
}

namespace {

// Progress line: which row, sequence and phase, with the table's ETA from the finished runs.
struct TableProgress {
  long total = 0, done = 0;
  double start = now_s();
  void phase(size_t ri, size_t nr, const std::string& method, size_t si, size_t ns,
             const std::string& seq, const std::string& phase) const {
    const double el = now_s() - start;
    const double eta = done > 0 ? el / done * double(total - done) : -1.0;
    log::info("[bench ", done, "/", total, " runs, ", format_duration(el), " elapsed, ETA ",
              done > 0 ? format_duration(eta) : std::string("?"), "] row ", ri + 1, "/", nr, " ",
              method, " | sequence ", si + 1, "/", ns, " ", seq, " | phase ", phase);
  }
};

}  // namespace

namespace {

std::string missing_reason(const std::string& dir) {
  return "real data not found at " + dir + " (--real-root DIR, or $SGNLF_SHARED_DIR/data/real)";
}

}  // namespace

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

CellOutcome execute_cell(const BenchOptions& opt, const BenchHooks& hooks, const TablePlan& plan,
                         const Cell& cell, std::map<std::string, PreparedSequence>& cache,
                         const Json& context) {
  const auto it = std::find_if(plan.sequences.begin(), plan.sequences.end(),
                               [&](const SequenceDef& d) { return d.name == cell.sequence; });
  require(it != plan.sequences.end(), "execute_cell: the plan has no sequence " + cell.sequence);
  const SequenceDef& sd = *it;
  const bool real = !opt.data_root.empty();
  const bool real_seq = !real && sd.is_real_dir();
  CellOutcome o;
  o.present = true;
  if (real_seq) {
    o.data_path = sequence_data_root(sd, opt);
    if (!fs::is_directory(o.data_path)) {
      o.status = "missing";
      o.error = missing_reason(o.data_path);
      return o;
    }
  }
  if (!cache.count(sd.name)) {
    const double ts = now_s();
    const std::string dir = (fs::path(opt.out_dir) / "data" / sd.name).string();
    BenchOptions popt = opt;  // a real sequence is loaded like a --data-root window
    if (real_seq) popt.data_root = o.data_path;
    try {
      PreparedSequence ps = hooks.prepare(sd, popt, dir);
      o.prepare_s = now_s() - ts;
      cache[sd.name] = ps;
    } catch (const std::exception& e) {
      // An optional real sequence that does not load is skipped like a missing one, so that
      // the twins' rows still finish.
      o.status = real_seq ? "unloadable" : "failed";
      o.error = real_seq ? "real data at " + o.data_path + " could not be loaded: " + e.what()
                         : std::string(e.what());
      return o;
    }
  }
  const PreparedSequence& ps = cache[sd.name];
  o.dataset = ps.dataset;
  pipeline::MethodRequest req;
  req.method = cell.method;
  req.scale = opt.scale;
  req.dataset_dir = ps.dataset_dir;
  fs::path run_dir = fs::path(opt.out_dir) / "runs" / cell.method / sd.name;
  if (plan.seeds.size() > 1) run_dir /= "seed-" + std::to_string(cell.seed);
  req.out_dir = run_dir.string();
  req.seed = cell.seed;
  req.device = opt.device;
  req.overrides = ps.overrides;
  req.context = context;
  try {
    const double tr = now_s();
    const pipeline::MethodResult res = hooks.run(req);
    const double wall = now_s() - tr;
    if (!res.implemented) {
      o.status = "not_implemented";
      return o;
    }
    o.entry = sequence_entry(sd.name, cell.seed, ps.dataset, res, req.out_dir, wall);
    o.status = "ok";
  } catch (const std::exception& e) {
    o.status = "failed";
    o.error = e.what();
  }
  return o;
}

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
                            error, real_names, plan.seeds));
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

Json run_table(const BenchOptions& opt, const BenchHooks& hooks, Json context) {
  const TablePlan plan = plan_table(opt, hooks);
  const bool real = !opt.data_root.empty();
  const double t0 = now_s();
  // Real sequences of a synthetic scale: run from their folder when it exists, else skipped
  // (recorded in `skipped_sequences`); averaged apart from the twins (make_row).
  std::set<std::string> dropped;
  for (const auto& sd : plan.sequences)
    if (!real && sd.is_real_dir() && !fs::is_directory(sequence_data_root(sd, opt))) {
      log::warn("[bench] sequence ", sd.name, " skipped: ",
                missing_reason(sequence_data_root(sd, opt)));
      dropped.insert(sd.name);
    }
  if (dropped.size() == plan.sequences.size())
    throw ConfigError("bench: table " + plan.table.name + " at scale " + opt.scale +
                      ": no sequence left to run (the real data of every chosen one is missing)");
  std::vector<CellOutcome> outcomes(plan.cells.size());
  for (const Cell& c : plan.cells)
    if (dropped.count(c.sequence)) {
      CellOutcome& o = outcomes[c.index];
      o.present = true;
      o.status = "missing";
      const auto& sd = *std::find_if(plan.sequences.begin(), plan.sequences.end(),
                                     [&](const SequenceDef& d) { return d.name == c.sequence; });
      o.data_path = sequence_data_root(sd, opt);
      o.error = missing_reason(o.data_path);
    }
  for (size_t ri = 0; ri < plan.table.rows.size(); ++ri)
    if (plan.row_state[ri] == "not_implemented")
      log::info("[bench] row ", plan.table.rows[ri].method, ": not implemented");

  TableProgress prog;
  for (const auto& c : plan.cells) prog.total += !dropped.count(c.sequence);
  std::map<std::string, PreparedSequence> cache;  // by sequence name, shared by rows and seeds
  std::set<std::string> stopped;  // rows that failed or are not implemented: not run further
  const auto row_index = [&](const std::string& m) {
    for (size_t i = 0; i < plan.table.rows.size(); ++i)
      if (plan.table.rows[i].method == m) return i;
    return size_t(0);
  };
  const auto seq_index = [&](const std::string& n) {
    for (size_t i = 0; i < plan.sequences.size(); ++i)
      if (plan.sequences[i].name == n) return i;
    return size_t(0);
  };
  for (const Cell& c : plan.cells) {
    if (stopped.count(c.method) || dropped.count(c.sequence)) continue;
    const size_t ri = row_index(c.method), si = seq_index(c.sequence);
    const bool real_seq = !real && plan.sequences[si].is_real_dir();
    const std::string seq_label =
        plan.seeds.size() > 1 ? c.sequence + " seed " + std::to_string(c.seed) : c.sequence;
    if (!cache.count(c.sequence))
      prog.phase(ri, plan.table.rows.size(), c.method, si, plan.sequences.size(), seq_label,
                 real || real_seq ? "load" : "simulate");
    prog.phase(ri, plan.table.rows.size(), c.method, si, plan.sequences.size(), seq_label,
               "train + evaluate");
    CellOutcome& o = outcomes[c.index];
    o = execute_cell(opt, hooks, plan, c, cache, context);
    if (o.status == "ok") {
      ++prog.done;
    } else if (o.status == "unloadable") {
      log::warn("[bench] sequence ", c.sequence, " skipped: ", o.error);
      dropped.insert(c.sequence);
    } else {
      if (o.status == "failed")
        log::warn("[bench] row ", c.method, " failed on ", seq_label, ": ", o.error);
      stopped.insert(c.method);
    }
    prog.total = 0;  // cells done, plus those still to run
    for (const auto& d : plan.cells)
      prog.total += outcomes[d.index].present
                        ? outcomes[d.index].status == "ok"
                        : !stopped.count(d.method) && !dropped.count(d.sequence);
  }
  TableHeader h;
  h.config = opt.to_json();
  h.command = opt.command;
  h.out_dir = opt.out_dir;
  h.real_root = opt.resolved_real_root();
  h.real = real;
  h.metric_definitions = hooks.metric_definitions ? hooks.metric_definitions() : Json();
  h.context = std::move(context);
  h.total_s = now_s() - t0;
  h.peak_rss_kib = peak_rss_kib();
  return assemble_table(plan, outcomes, h);
}

std::pair<std::string, std::string> write_outputs(const Json& results, const std::string& out_dir) {
  fs::create_directories(out_dir);
  const std::string json_path = (fs::path(out_dir) / "results.json").string();
  const std::string md_path = (fs::path(out_dir) / "table.md").string();
  write_json_file(json_path, results);
  write_text_file(md_path, render_markdown(results));
  return {json_path, md_path};
}

}  // namespace sgnlf::harness
