#include "harness/runner.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <map>

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
  }
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
      try {
        if (!prepared.count(sd.name)) {
          prog.phase(ri, t.rows.size(), row.method, si, seqs.size(), sd.name,
                     real ? "load" : "simulate");
          const double ts = now_s();
          const std::string dir = (fs::path(opt.out_dir) / "data" / sd.name).string();
          prepared[sd.name] = hooks.prepare(sd, opt, dir);
          prepare_s.push_back(now_s() - ts);
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
        status = "failed";
        error = sd.name + ": " + e.what();
        log::warn("[bench] row ", row.method, " failed on ", sd.name, ": ", e.what());
      }
    }
    if (status != "ok") prog.total -= long(seqs.size()) - long(entries.size());
    rows.push_back(make_row(t.name, row, status, status == "ok" ? entries : std::vector<Json>{},
                            error));
    if (status == "failed") rows.back()["sequences"] = entries;  // keep what finished
  }

  Json seq_list = Json::array();
  for (const auto& sd : seqs) {
    Json s = sd.to_json();
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
  r["sequences"] = seq_list;
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
