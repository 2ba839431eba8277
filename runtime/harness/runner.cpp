#include "harness/runner.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "core/config.hpp"
#include "core/log.hpp"
#include "core/progress.hpp"
#include "harness/clock.hpp"
#include "harness/context.hpp"
#include "harness/markdown.hpp"
#include "harness/results.hpp"

namespace sgnlf::harness {
namespace fs = std::filesystem;

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
  req.device_profile = opt.device_profile;
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
