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

Json BenchOptions::to_json() const {
  Json j{{"table", table},   {"scale", scale}, {"data_root", data_root},
         {"device", device}, {"seed", seed},   {"roofline", roofline}};
  if (!rows.empty()) j["rows"] = rows;
  if (!sequences.empty()) j["sequences"] = sequences;
  return j;
}

namespace {

double now_s() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

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

Json run_table(const BenchOptions& opt, const BenchHooks& hooks, Json context) {
  opt.validate();
  const TableDef t = table_def(opt.table);
  const bool real = !opt.data_root.empty();
  auto seqs = table_sequences(t, opt.scale, real);
  if (!opt.sequences.empty())
    seqs.erase(std::remove_if(seqs.begin(), seqs.end(),
                              [&](const SequenceDef& d) {
                                return std::find(opt.sequences.begin(), opt.sequences.end(),
                                                 d.name) == opt.sequences.end();
                              }),
               seqs.end());
  // Real sequences of a synthetic scale: run from their folder when it exists, else skipped
  // (recorded in `skipped_sequences`); averaged apart from the twins (make_row).
  Json skipped = Json::array();
  std::vector<std::string> real_names;
  bool any_real_dir = false;
  if (!real) {
    std::vector<SequenceDef> kept;
    for (const auto& sd : seqs) {
      if (!sd.is_real_dir()) {
        kept.push_back(sd);
        continue;
      }
      any_real_dir = true;
      const std::string dir = sequence_data_root(sd, opt);
      if (fs::is_directory(dir)) {
        kept.push_back(sd);
        real_names.push_back(sd.name);
        continue;
      }
      const std::string reason = "real data not found at " + dir +
                                 " (--real-root DIR, or $SGNLF_SHARED_DIR/data/real)";
      log::warn("[bench] sequence ", sd.name, " skipped: ", reason);
      skipped.push_back(Json{{"name", sd.name}, {"real_dir", sd.real_dir}, {"path", dir},
                             {"reason", reason}});
    }
    seqs = kept;
  }
  if (seqs.empty())
    throw ConfigError("bench: table " + t.name + " at scale " + opt.scale +
                      ": no sequence left to run (the real data of every chosen one is missing)");
  const auto is_real_seq = [&](const std::string& name) {
    return std::find(real_names.begin(), real_names.end(), name) != real_names.end();
  };
  const auto selected = [&](const std::string& method) {
    return opt.rows.empty() ||
           std::find(opt.rows.begin(), opt.rows.end(), method) != opt.rows.end();
  };
  const double t0 = now_s();

  std::vector<bool> impl;
  long implemented_rows = 0;
  for (const auto& row : t.rows) {
    impl.push_back(hooks.implemented && hooks.implemented(row.method));
    if (!impl.back()) log::info("[bench] row ", row.method, ": not implemented");
    implemented_rows += impl.back() && selected(row.method);
  }
  TableProgress prog;
  prog.total = implemented_rows * long(seqs.size());

  std::map<std::string, PreparedSequence> prepared;  // by sequence name, shared by rows
  std::set<std::string> unloadable;  // real sequences whose folder is there but did not load
  std::vector<double> prepare_s;
  Json runs = Json::array(), rows = Json::array();
  for (size_t ri = 0; ri < t.rows.size(); ++ri) {
    const RowDef& row = t.rows[ri];
    if (!selected(row.method)) {
      rows.push_back(make_row(t.name, row, "skipped", {}));
      continue;
    }
    if (!impl[ri]) {
      rows.push_back(make_row(t.name, row, "not_implemented", {}));
      continue;
    }
    std::vector<Json> entries;
    std::string status = "ok", error;
    for (size_t si = 0; si < seqs.size() && status == "ok"; ++si) {
      const SequenceDef& sd = seqs[si];
      if (unloadable.count(sd.name)) continue;
      bool preparing = false;
      try {
        if (!prepared.count(sd.name)) {
          preparing = true;
          const bool real_seq = is_real_seq(sd.name);
          prog.phase(ri, t.rows.size(), row.method, si, seqs.size(), sd.name,
                     real || real_seq ? "load" : "simulate");
          const double ts = now_s();
          const std::string dir = (fs::path(opt.out_dir) / "data" / sd.name).string();
          BenchOptions popt = opt;  // a real sequence is loaded like a --data-root window
          if (real_seq) popt.data_root = sequence_data_root(sd, opt);
          prepared[sd.name] = hooks.prepare(sd, popt, dir);
          prepare_s.push_back(now_s() - ts);
          preparing = false;
        }
        const PreparedSequence& ps = prepared[sd.name];
        pipeline::MethodRequest req;
        req.method = row.method;
        req.scale = opt.scale;
        req.dataset_dir = ps.dataset_dir;
        req.out_dir = (fs::path(opt.out_dir) / "runs" / row.method / sd.name).string();
        req.seed = opt.seed;
        req.device = opt.device;
        req.overrides = ps.overrides;
        prog.phase(ri, t.rows.size(), row.method, si, seqs.size(), sd.name, "train + evaluate");
        const double tr = now_s();
        const pipeline::MethodResult res = hooks.run(req);
        const double wall = now_s() - tr;
        if (!res.implemented) {
          status = "not_implemented";
          break;
        }
        entries.push_back(sequence_entry(sd.name, opt.seed, ps.dataset, res, req.out_dir, wall));
        runs.push_back(Json{{"method", row.method},
                            {"sequence", sd.name},
                            {"seed", opt.seed},
                            {"dataset_seed", ps.dataset.value("seed", Json(nullptr))}});
        ++prog.done;
      } catch (const std::exception& e) {
        if (preparing && is_real_seq(sd.name)) {
          // An optional real sequence that does not load is skipped like a missing one, so
          // that the twins' rows still finish.
          const std::string dir = sequence_data_root(sd, opt);
          const std::string reason = "real data at " + dir + " could not be loaded: " + e.what();
          log::warn("[bench] sequence ", sd.name, " skipped: ", reason);
          skipped.push_back(Json{{"name", sd.name}, {"real_dir", sd.real_dir}, {"path", dir},
                                 {"reason", reason}});
          unloadable.insert(sd.name);
          real_names.erase(std::find(real_names.begin(), real_names.end(), sd.name));
          for (size_t rj = ri; rj < t.rows.size(); ++rj)
            prog.total -= impl[rj] && selected(t.rows[rj].method) ? 1 : 0;
          continue;
        }
        status = "failed";
        error = sd.name + ": " + e.what();
        log::warn("[bench] row ", row.method, " failed on ", sd.name, ": ", e.what());
      }
    }
    if (status != "ok")
      prog.total -= long(seqs.size() - unloadable.size()) - long(entries.size());
    rows.push_back(make_row(t.name, row, status, status == "ok" ? entries : std::vector<Json>{},
                            error, real_names));
    if (status == "failed") rows.back()["sequences"] = entries;  // keep what finished
  }

  Json seq_list = Json::array();
  for (const auto& sd : seqs) {
    if (unloadable.count(sd.name)) continue;  // listed in skipped_sequences
    Json s = sd.to_json();
    if (is_real_seq(sd.name)) s["real_path"] = sequence_data_root(sd, opt);
    if (prepared.count(sd.name)) s["dataset"] = prepared[sd.name].dataset;
    seq_list.push_back(s);
  }
  context["peak_rss_kib"] = peak_rss_kib();

  Json r;
  r["schema"] = kSchemaName;
  r["schema_version"] = kSchemaVersion;
  r["kind"] = "table";
  r["table"] = t.name;
  r["title"] = t.title;
  r["scale"] = opt.scale;
  r["data"] = real ? "real" : "synthetic";
  r["created_utc"] = utc_now();
  r["command"] = opt.command;
  r["out_dir"] = opt.out_dir;
  r["config"] = opt.to_json();
  r["config_hash"] = config_hash(r["config"]);
  r["seeds"] = Json{{"table_seed", opt.seed}, {"runs", runs}};
  r["context"] = context;
  r["columns"] = t.columns;
  r["extra_columns"] = t.extra_columns;
  r["metric_definitions"] = hooks.metric_definitions ? hooks.metric_definitions() : Json();
  r["sequences"] = seq_list;
  r["skipped_sequences"] = skipped;
  if (any_real_dir) r["real_root"] = opt.resolved_real_root();
  r["rows"] = rows;
  r["timings"] = Json{{"prepare_s", summarize(prepare_s)}, {"total_s", now_s() - t0}};
  r["peak_rss_kib"] = peak_rss_kib();
  return r;
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
