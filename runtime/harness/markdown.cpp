#include "harness/markdown.hpp"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <sstream>

#include "core/config.hpp"
#include "harness/results.hpp"
#include "harness/tables.hpp"

namespace sgnlf::harness {
namespace {

std::string header(const std::string& key) {
  const MetricInfo* m = metric_info(key);
  if (!m) return key;
  std::string h = m->label;
  if (!m->unit.empty()) h += " (" + m->unit + ")";
  return h + m->arrow();
}

std::string signed_fmt(const std::string& key, double v) {
  const MetricInfo* m = metric_info(key);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%+.*f", m ? m->digits : 4, v);
  return buf;
}

std::string status_cell(const Json& row) {
  const std::string s = row.value("status", "");
  if (s == "not_implemented") return "not implemented";
  if (s == "failed") return "failed";
  if (s == "skipped") return "not run (--rows)";
  if (s == "not_run") return "not run";
  return "—";
}

// A combined table's row label (results/schema.md "Combined tables"): marks a row whose
// means leave sequences out or whose runs were made with another config than today's.
std::string row_label(const Json& row) {
  std::string l = row.value("label", row.value("method", ""));
  const Json& nr = row.contains("sequences_not_run") ? row["sequences_not_run"] : Json();
  if (row.value("status", "") == "ok" && nr.is_array() && !nr.empty())
    l += " (partial: " + std::to_string(row.value("sequences", Json::array()).size()) + " of " +
         std::to_string(row["sequences"].size() + nr.size()) + " sequences)";
  if (row.value("stale", Json()) == Json(true)) l += " (stale config)";
  return l;
}

const Json& get_or_null(const Json& j, const std::string& k) {
  static const Json null_json;
  return j.is_object() && j.contains(k) ? j[k] : null_json;
}

std::vector<std::string> str_list(const Json& j) {
  std::vector<std::string> v;
  if (j.is_array())
    for (const auto& x : j) v.push_back(x.get<std::string>());
  return v;
}

// The naive baseline the pipeline scores beside each run (extra.naive_baseline: the nearest
// training scan moved with the ground-truth poses); it depends on the data only, so the
// first running row's copy stands for all. Empty object when no run reports it.
Json naive_for(const Json& r, const std::string& sequence) {
  for (const auto& row : r.value("rows", Json::array()))
    for (const auto& s : row.value("sequences", Json::array()))
      if (s.value("sequence", "") == sequence)
        for (const auto& run : s.contains("runs") ? s["runs"] : Json::array({s}))  // several seeds
          if (run.contains("extra") && run["extra"].is_object() &&
              run["extra"].contains("naive_baseline"))
            return run["extra"]["naive_baseline"];
  return Json::object();
}

// Whether a run of `sequence` says its reference poses are planar (pose_metrics.ate_reference,
// metrics/evaluate.hpp; results before it do not say, and render as before).
bool planar_reference(const Json& r, const std::string& sequence) {
  for (const auto& row : r.value("rows", Json::array()))
    for (const auto& s : row.value("sequences", Json::array()))
      if (s.value("sequence", "") == sequence)
        for (const auto& run : s.contains("runs") ? s["runs"] : Json::array({s}))  // several seeds
          if (get_or_null(get_or_null(run, "pose_metrics"), "ate_reference") == Json("horizontal"))
            return true;
  return false;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// Names of the real sequences of a synthetic scale (sequences[] with `real_dir`), or of the
// twins: the two groups are averaged and shown apart.
std::vector<std::string> sequence_names(const Json& r, bool real_dir) {
  std::vector<std::string> v;
  for (const auto& seq : r.value("sequences", Json::array()))
    if (seq.contains("real_dir") == real_dir) v.push_back(seq.value("name", ""));
  return v;
}

}  // namespace

std::string format_metric(const std::string& key, const Json& v) {
  if (!v.is_number()) return "—";
  const MetricInfo* m = metric_info(key);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", m ? m->digits : 4, v.get<double>());
  return buf;
}

// "mean ± sd" when `sd` is a number (several seeds), else the mean alone.
static std::string format_mean_sd(const std::string& key, const Json& mean, const Json& sd) {
  if (!mean.is_number() || !sd.is_number()) return format_metric(key, mean);
  return format_metric(key, mean) + " ± " + format_metric(key, sd);
}

// One table of the rows' means (`mean_key`: "mean" over the twins, "mean_real" over the real
// sequences of a synthetic scale): ours | paper | Δ for each of the paper's columns, then
// ours-only columns, then the naive baseline's mean over `naive_seqs`.
void main_table(std::ostringstream& o, const Json& r, const std::vector<std::string>& cols,
                const std::vector<std::string>& extra, const std::string& mean_key,
                const std::vector<std::string>& naive_seqs, bool& any_unverified,
                const std::function<std::string(const Json&)>& mark) {
  o << "| method |";
  for (const auto& c : cols) o << " " << header(c) << " ours | paper | Δ |";
  for (const auto& c : extra) o << " " << header(c) << " |";
  o << "\n|---|";
  for (size_t i = 0; i < cols.size(); ++i) o << "---:|---:|---:|";
  for (size_t i = 0; i < extra.size(); ++i) o << "---:|";
  o << "\n";
  for (const auto& row : r.value("rows", Json::array())) {
    const bool ok = row.value("status", "") == "ok";
    const Json& mean = get_or_null(row, mean_key);
    o << "| " << row_label(row) << mark(row) << " |";
    for (const auto& c : cols) {
      Json paper = get_or_null(row["paper"], c);
      std::string mark;
      if (paper.is_null() && !get_or_null(row["paper_unverified"], c).is_null()) {
        paper = row["paper_unverified"][c];
        mark = "†";
        any_unverified = true;
      }
      const Json& ours = ok ? get_or_null(mean, c) : Json();
      const Json& sd = ok ? get_or_null(get_or_null(row, mean_key + "_sd"), c) : Json();
      o << " " << (ok ? format_mean_sd(c, ours, sd) : status_cell(row)) << " | "
        << format_metric(c, paper) << mark << " | "
        << (ours.is_number() && paper.is_number()
                ? signed_fmt(c, ours.get<double>() - paper.get<double>())
                : "—")
        << " |";
    }
    for (const auto& c : extra)
      o << " " << (ok ? format_mean_sd(c, get_or_null(mean, c),
                                        get_or_null(get_or_null(row, mean_key + "_sd"), c))
                      : status_cell(row))
        << " |";
    o << "\n";
  }
  // Reference row: the naive baseline, mean over the sequences that report it.
  std::vector<Json> naive;
  for (const auto& name : naive_seqs) {
    const Json n = naive_for(r, name);
    if (!n.empty()) naive.push_back(n);
  }
  if (!naive.empty()) {
    o << "| *naive baseline (nearest training scan)* |";
    auto mean = [&](const std::string& c) -> Json {
      double sum = 0;
      for (const auto& n : naive) {
        if (!n.contains(c) || !n[c].is_number()) return Json();
        sum += n[c].get<double>();
      }
      return sum / double(naive.size());
    };
    for (const auto& c : cols) o << " " << format_metric(c, mean(c)) << " | | |";
    for (const auto& c : extra) o << " " << format_metric(c, mean(c)) << " |";
    o << "\n";
  }
}

std::string seeds_mark(const Json& row, uint64_t table_seed) {
  std::vector<std::vector<uint64_t>> lists;
  for (const auto& e : row.value("sequences", Json::array())) lists.push_back(entry_seeds(e));
  if (lists.empty()) return "";
  const auto text = [](const std::vector<uint64_t>& v) {
    std::string s = v.size() > 1 ? "seeds " : "seed ";
    for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + std::to_string(v[i]);
    return s;
  };
  const bool same = std::all_of(lists.begin(), lists.end(), [&](const auto& l) { return l == lists[0]; });
  if (same)
    return lists[0].size() == 1 && lists[0][0] == table_seed ? std::string() : text(lists[0]);
  // Different seeds by sequence: the most seeds any sequence has, and on how many.
  const auto most = *std::max_element(lists.begin(), lists.end(),
                                      [](const auto& a, const auto& b) { return a.size() < b.size(); });
  const auto k = std::count(lists.begin(), lists.end(), most);
  return text(most) + " on " + std::to_string(k) + " of " + std::to_string(lists.size()) + " sequences";
}

std::string render_markdown(const Json& r) {
  std::ostringstream o;
  const auto cols = str_list(r.value("columns", Json::array()));
  const auto extra = str_list(r.value("extra_columns", Json::array()));
  const Json& ctx = r.value("context", Json::object());
  o << "# " << r.value("title", r.value("table", "")) << "\n\n";
  o << "Table `" << r.value("table", "") << "`, scale `" << r.value("scale", "") << "`, "
    << r.value("data", "") << " data, ";
  const Json& seeds = get_or_null(r["config"], "seeds");
  const bool several = seeds.is_array() && seeds.size() > 1;
  if (several) {
    o << "seeds ";
    for (size_t i = 0; i < seeds.size(); ++i) o << (i ? ", " : "") << seeds[i].dump();
  } else {
    o << "seed " << get_or_null(r["config"], "seed").dump();
  }
  o << ", " << r.value("created_utc", "") << ".\n";
  // Every run cell on every seed (bench --seeds), or, in a combined table, some cells on some
  // seeds: those are marked with their seeds.
  std::vector<uint64_t> table_seeds;
  if (several) table_seeds = seeds.get<std::vector<uint64_t>>();
  bool every_cell_all_seeds = several;
  for (const auto& row : r.value("rows", Json::array()))
    for (const auto& e : row.value("sequences", Json::array()))
      every_cell_all_seeds &= row.value("status", "") != "ok" || entry_seeds(e) == table_seeds;
  const uint64_t first_seed = several ? table_seeds.front() : get_or_null(r["config"], "seed").is_number_unsigned()
                                                                 ? r["config"]["seed"].get<uint64_t>()
                                                                 : uint64_t(1);
  // The row label with the seeds of a row run on other seeds than the table's one seed, or
  // than every seed of a several-seed table.
  const auto mark = [&](const Json& row) {
    const std::string m = every_cell_all_seeds ? std::string() : seeds_mark(row, first_seed);
    return m.empty() ? m : " (" + m + ")";
  };
  if (every_cell_all_seeds)
    o << "Ours: mean ± sample standard deviation over the " << seeds.size()
      << " seeds (of the per-seed means over sequences in the main tables).\n";
  else if (several)
    o << "Ours: one run per cell (row × sequence) at seed " << first_seed
      << ", except where a row or sequence is marked with its seeds: there the mean ± sample "
         "standard deviation over those seeds (in the main tables, of the per-seed means over "
         "sequences; a row whose sequences ran different seeds: the mean of each sequence's "
         "seed mean, ± the spread over the seeds all its sequences share, results/schema.md).\n";
  if (!r.value("command", "").empty()) o << "Command: `" << r.value("command", "") << "`\n";
  o << "\n";

  // Main table: the rows' means over the synthetic twins (or the --data-root windows).
  bool any_unverified = false;
  const auto twins = sequence_names(r, false), reals = sequence_names(r, true);
  main_table(o, r, cols, extra, "mean", twins, any_unverified, mark);
  o << "\nΔ = ours − paper. Paper numbers: " << paper_source(r.value("table", "")) << ".";
  if (any_unverified) o << " † from third-party notes, not verified.";
  o << " F-score compares squared distances with 0.05, i.e. a √0.05 ≈ 0.224 m threshold "
       "(protocol §4).";
  if (r.value("data", "") == "synthetic" && reals.empty())
    o << " Ours are on the built-in synthetic twins, not on the real sequences: compare "
         "orderings and gaps, not digits.";
  if (r.value("data", "") == "synthetic" && !reals.empty())
    o << " Ours above are means over the built-in synthetic twins (" << join(twins)
      << "), not the real sequences: compare orderings and gaps, not digits. The real "
         "sequence" << (reals.size() > 1 ? "s " : " ") << join(reals)
      << (reals.size() > 1 ? " are in their" : " is in its") << " own table below, not in these means.";
  o << "\n";
  for (const auto& row : r.value("rows", Json::array()))
    if (row.value("status", "") == "failed")
      o << "\n**" << row.value("method", "") << " failed:** " << row.value("error", "") << "\n";
  for (const auto& sk : r.value("skipped_sequences", Json::array()))
    o << "\n**Sequence " << sk.value("name", "") << " not run:** " << sk.value("reason", "")
      << "\n";

  // Real sequences of a synthetic scale: the same rows, averaged over them alone.
  if (!reals.empty()) {
    o << "\n## Real data: " << join(reals) << " (not in the means above)\n\n";
    for (const auto& seq : r.value("sequences", Json::array()))
      if (seq.contains("real_dir"))
        o << "- " << seq.value("name", "") << ": " << seq.value("real_path", seq.value("real_dir", ""))
          << (seq.contains("sequence") ? " (" + seq.value("sequence", "") + ")" : std::string())
          << "\n";
    o << "\nOurs: " << (reals.size() > 1 ? "mean over these sequences" : "this sequence")
      << " (`mean_real`); paper: the paper's numbers on its own sequences of the dataset.\n\n";
    main_table(o, r, cols, extra, "mean_real", reals, any_unverified, mark);
  }

  // Per-sequence tables.
  const std::vector<std::string> all = [&] {
    auto v = cols;
    v.insert(v.end(), extra.begin(), extra.end());
    return v;
  }();
  for (const auto& seq : r.value("sequences", Json::array())) {
    const std::string name = seq.value("name", "");
    o << "\n## Sequence " << name << (seq.contains("real_dir") ? " — real data" : "");
    const Json& ds = get_or_null(seq, "dataset");
    if (ds.is_object() && ds.contains("frames"))
      o << " (" << ds["frames"].dump() << " frames"
        << (ds.contains("test") ? ", test " + ds["test"].dump() : std::string()) << ")";
    o << "\n\n| method |";
    for (const auto& c : all) o << " " << header(c) << " |";
    o << "\n|---|";
    for (size_t i = 0; i < all.size(); ++i) o << "---:|";
    o << "\n";
    for (const auto& row : r.value("rows", Json::array())) {
      Json m, msd;
      std::string mark;
      for (const auto& s : row.value("sequences", Json::array()))
        if (s.value("sequence", "") == name) {
          const auto ks = entry_seeds(s);
          if (!every_cell_all_seeds && (ks.size() > 1 || ks.front() != first_seed)) {
            mark = ks.size() > 1 ? " (seeds" : " (seed";
            for (size_t i = 0; i < ks.size(); ++i) mark += (i ? ", " : " ") + std::to_string(ks[i]);
            mark += ")";
          }
          if (s.value("stale", Json()) == Json(true)) mark += " (stale config)";
          m = s.value("metrics", Json::object());
          msd = s.value("metrics_sd", Json::object());
          const Json pose = s.value("pose_metrics", Json());
          if (pose.is_object())
            for (auto it = pose.begin(); it != pose.end(); ++it) m[it.key()] = it.value();
        }
      o << "| " << row.value("label", "") << mark << " |";
      const bool not_run = row.value("status", "") == "ok" && !m.is_object();
      for (const auto& c : all)
        o << " "
          << (m.is_object() ? format_mean_sd(c, get_or_null(m, c), get_or_null(msd, c))
              : not_run     ? std::string("not run")
                            : status_cell(row))
          << " |";
      o << "\n";
    }
    const Json naive = naive_for(r, name);
    if (!naive.empty()) {
      o << "| *naive baseline* |";
      for (const auto& c : all) o << " " << format_metric(c, get_or_null(naive, c)) << " |";
      o << "\n";
    }
    if (planar_reference(r, name))
      o << "\nThe reference poses of " << name << " are planar (every z equal, as nuScenes' ego "
           "poses): judge the poses by the horizontal ATE, not the 3D one.\n";
  }

  // Timings (seconds, median over repetitions).
  o << "\n## Timings (s, median [min–max] over n repetitions)\n\n";
  for (const auto& row : r.value("rows", Json::array())) {
    const Json& t = row.value("timings", Json::object());
    if (t.empty()) continue;
    o << "- " << row.value("label", "") << ":";
    for (auto it = t.begin(); it != t.end(); ++it) {
      if (!it.value().contains("median")) continue;
      char buf[160];
      std::snprintf(buf, sizeof buf, " %s %.3g [%.3g–%.3g] n=%d;", it.key().c_str(),
                    it.value()["median"].get<double>(), it.value()["min"].get<double>(),
                    it.value()["max"].get<double>(), it.value()["n"].get<int>());
      o << buf;
    }
    o << "\n";
  }

  o << render_provenance(r);

  // Context.
  o << "\n## Context\n\n";
  if (r.contains("combined_from")) o << "- of the first input; each row's own: Provenance above\n";
  const Json& git = get_or_null(ctx, "git");
  if (git.is_object())
    o << "- git " << git.value("sha", "?").substr(0, 12)
      << (git.value("dirty", Json(false)) == Json(true) ? " (dirty)" : "") << "\n";
  const Json& cl = get_or_null(ctx, "opencl");
  if (cl.is_object())
    o << "- OpenCL: " << cl.value("platform", "") << " / " << cl.value("device", "")
      << ", driver " << cl.value("driver_version", "") << "\n";
  const Json& m = get_or_null(ctx, "machine");
  if (m.is_object())
    o << "- machine: " << m.value("cpu_model", "") << ", " << get_or_null(m, "logical_cores").dump()
      << " logical cores, " << m.value("os", "") << "\n";
  const Json& rf = get_or_null(ctx, "roofline");
  if (rf.is_object() && rf.contains("peak_gflops")) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "- roofline (measured, best of %d): %.1f GFLOP/s fp32, %.1f GB/s triad, "
                  "%.1f GB/s copy (medians %.1f, %.1f, %.1f)\n",
                  rf["peak_gflops"].value("n", 0), rf.value("peak_gflops_best", 0.0),
                  rf.value("triad_gbs_best", 0.0), rf.value("copy_gbs_best", 0.0),
                  rf["peak_gflops"].value("median", 0.0), rf["triad_gbs"].value("median", 0.0),
                  rf["copy_gbs"].value("median", 0.0));
    o << buf;
    if (rf.contains("gathers_per_s_best")) {
      std::snprintf(buf, sizeof buf, "- random float2 reads (measured, best): %.0f M/s\n",
                    rf.value("gathers_per_s_best", 0.0) * 1e-6);
      o << buf;
    }
  }
  if (r.contains("peak_rss_kib"))
    o << "- peak host memory: " << r["peak_rss_kib"].get<long>() / 1024 << " MiB\n";
  return o.str();
}

}  // namespace sgnlf::harness
