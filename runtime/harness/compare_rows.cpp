// How `sgnlf compare` holds a new result to its baseline once the mode (tight or loose) is
// chosen (compare.cpp chooses it): every row, sequence, seed run and timing of the baseline
// against the new result; each metric within metric_tolerance() of tables.json's "tolerances"
// in its better direction (results/schema.md), plus, when loose, twice the standard error of
// the seeds' spread (results/schema.md "Several seeds"); a tight one-seed run against a
// several-seed baseline compared with that seed's run; timings by their median ratio.
#include "harness/compare_rows.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/config.hpp"
#include "harness/stats.hpp"
#include "harness/tables.hpp"

namespace sgnlf::harness {
namespace compare_detail {

std::string str(const Json& j, const std::string& k) {
  const Json& v = at(j, k);
  return v.is_string() ? v.get<std::string>() : std::string();
}
const Json& arr(const Json& j, const std::string& k) {
  static const Json empty = Json::array();
  const Json& v = at(j, k);
  return v.is_array() ? v : empty;
}

const Json* find_by(const Json& arr, const std::string& key, const std::string& value) {
  if (!arr.is_array()) return nullptr;
  for (const auto& x : arr)
    if (str(x, key) == value) return &x;
  return nullptr;
}

// The run of `seed` in a several-seed entry's runs[] (nullptr when it has none).
const Json* run_of_seed(const Json& entry, const Json& seed) {
  for (const auto& x : arr(entry, "runs"))
    if (at(x, "seed") == seed) return &x;
  return nullptr;
}

namespace {

std::string fmt(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

Json merged_metrics(const Json& seq) {
  Json m = at(seq, "metrics").is_object() ? at(seq, "metrics") : Json::object();
  const Json& p = at(seq, "pose_metrics");
  if (p.is_object())
    for (auto it = p.begin(); it != p.end(); ++it) m[it.key()] = it.value();
  return m;
}

// The seed every sequence of a row ran alone (one-seed entries of one seed), else null.
Json one_seed(const Json& row) {
  Json seed;
  for (const auto& e : arr(row, "sequences")) {
    if (!at(e, "runs").is_null() || (!seed.is_null() && at(e, "seed") != seed)) return nullptr;
    seed = at(e, "seed");
  }
  return seed;
}

}  // namespace

void Comparer::metrics(const std::string& where, const Json& fresh, const Json& base,
                       Spread fresh_spread, Spread base_spread) {
  if (!base.is_object()) return;
  for (auto it = base.begin(); it != base.end(); ++it) {
    const std::string& k = it.key();
    if (!it.value().is_number()) continue;  // null in the baseline: nothing to hold
    const std::string w = where + " / " + k;
    const Json& nv = at(fresh, k);
    if (!nv.is_number()) {
      add("missing", true, w, "metric missing or null in the new result (baseline " +
                                  fmt(it.value().get<double>()) + ")");
      continue;
    }
    const double b = it.value().get<double>(), n = nv.get<double>();
    ++rep.metrics_compared;
    if (!std::isfinite(n)) {
      add("regression", true, w, "not finite: " + fmt(n));
      continue;
    }
    double tol = metric_tolerance(k, rep.mode, b);
    std::string spread_note;
    // Loose, both sides means over several seeds: allow twice the standard error of the
    // difference of the two means (Welch) on top of the tolerance. One side a single run, the
    // other a mean over several seeds: the run is one more draw of the other side's spread,
    // so the difference's standard error is sd·√(1 + 1/n). Tight comparisons stay tight: one
    // seed is deterministic on one device, so the spread is no noise there.
    static const Json none;
    const auto sd_of = [&](const Spread& sp) -> const Json& {
      return sp.n >= 2 && sp.sd ? at(*sp.sd, k) : none;
    };
    const Json& sn = sd_of(fresh_spread);
    const Json& sb = sd_of(base_spread);
    if (rep.mode == "loose" && (sn.is_number() || sb.is_number())) {
      double se = -1;
      if (sn.is_number() && sb.is_number()) {
        const double a = sn.get<double>(), c = sb.get<double>();
        se = std::sqrt(a * a / double(fresh_spread.n) + c * c / double(base_spread.n));
      } else if (sb.is_number() && fresh_spread.n < 2) {
        se = sb.get<double>() * std::sqrt(1.0 + 1.0 / double(base_spread.n));
      } else if (sn.is_number() && base_spread.n < 2) {
        se = sn.get<double>() * std::sqrt(1.0 + 1.0 / double(fresh_spread.n));
      }
      if (se >= 0) {
        tol += 2.0 * se;
        ++rep.seed_spread_used;
        spread_note = " incl. 2 × " + fmt(se) + " seed standard error (" +
                      std::to_string(std::max<size_t>(fresh_spread.n, 1)) + " vs " +
                      std::to_string(std::max<size_t>(base_spread.n, 1)) + " seeds)";
      }
    }
    const MetricInfo* info = metric_info(k);
    const std::string detail = "new " + fmt(n) + " vs baseline " + fmt(b) + " (diff " +
                               fmt(n - b) + ", tolerance " + fmt(tol) + spread_note + ")";
    if (!info || !info->judged()) {
      // No direction (a diagnostic, or a metric tables.json does not describe): a change
      // beyond the tolerance is reported, never a regression (a stale baseline under --strict).
      if (std::fabs(n - b) > tol)
        add("changed", opt.strict, w,
            std::string(info ? "a diagnostic without a better direction" : "a metric tables.json does not describe") +
                ", changed beyond tolerance: " + detail);
      continue;
    }
    const double worse = info->lower_better ? n - b : b - n;
    if (worse > tol)
      add("regression", true, w, "worse: " + detail);
    else if (-worse > tol)
      add("improved", opt.strict, w, "better beyond tolerance: " + detail);
  }
  if (fresh.is_object())
    for (auto it = fresh.begin(); it != fresh.end(); ++it)
      if (!base.contains(it.key()) && it.value().is_number())
        add("note", false, where + " / " + it.key(), "new metric, not in the baseline");
}

void Comparer::timings(const std::string& where, const Json& fresh, const Json& base,
                       bool same_dev, int min_reps, double max_ratio) {
  if (!opt.timings || !base.is_object()) return;
  for (auto it = base.begin(); it != base.end(); ++it) {
    const auto rb = repetitions(it.value());
    const auto rn = repetitions(at(fresh, it.key()));
    if (!same_dev || int(rb.size()) < min_reps || int(rn.size()) < min_reps ||
        rb.empty() || rn.empty()) {
      ++rep.timings_skipped;
      continue;
    }
    ++rep.timings_compared;
    const double mb = median(rb), mn = median(rn);
    if (mb > 0 && mn / mb > max_ratio)
      add("timing", true, where + " / " + it.key(),
          "median " + fmt(mn) + " s vs baseline " + fmt(mb) + " s: ratio " + fmt(mn / mb) +
              " > " + fmt(max_ratio) + " over " + std::to_string(rn.size()) + "/" +
              std::to_string(rb.size()) + " repetitions");
  }
}

void compare_rows(Comparer& c, const Json& fresh, const Json& base, bool same_dev, int min_reps,
                  double max_ratio) {
  for (const auto& brow : arr(base, "rows")) {
    const std::string m = str(brow, "method");
    const Json* nrow = find_by(at(fresh, "rows"), "method", m);
    if (!nrow) {
      if (c.opt.subset)
        c.add("note", false, m, "row not run (subset comparison)");
      else
        c.add("missing", true, m, "row missing from the new result");
      continue;
    }
    const std::string bs = str(brow, "status"), ns = str(*nrow, "status");
    if (c.opt.subset && ns == "skipped") {  // left out by --rows: nothing of it ran
      c.add("note", false, m, "row not run (subset comparison)");
      continue;
    }
    if (bs == "ok" && ns != "ok") {
      c.add("regression", true, m, "row was ok in the baseline, now " + ns +
                                       (at(*nrow, "error").is_string() ? ": " + (*nrow)["error"].get<std::string>() : ""));
      continue;
    }
    if (bs != "ok") {
      if (ns == "ok") c.add("note", false, m, "row now runs (baseline: " + bs + "); update the baseline");
      continue;
    }
    const auto row_spread = [](const Json& row, const std::string& key) {
      return Spread{&at(row, key + "_sd"), arr(row, key + "_by_seed").size()};
    };
    // A subset run's row mean covers other sequences than the whole table's: compare the
    // means only over the same sequences.
    const auto names = [](const Json& row) {
      std::vector<std::string> v;
      for (const auto& s : arr(row, "sequences")) v.push_back(str(s, "sequence"));
      std::sort(v.begin(), v.end());
      return v;
    };
    const bool same_sequences = names(*nrow) == names(brow);
    if (c.opt.subset && !same_sequences) {
      c.add("note", false, m + " / mean", "not compared: the new result ran other sequences");
    } else {
      // Tight, a one-seed row against a several-seed one: the baseline's mean of that seed.
      const Json seed = one_seed(*nrow);
      const auto mean_of = [&](const std::string& key) -> const Json& {
        if (c.rep.mode == "tight" && !seed.is_null() && !at(*nrow, key + "_by_seed").is_array())
          for (const auto& x : arr(brow, key + "_by_seed"))
            if (at(x, "seed") == seed) return at(x, "mean");
        return at(brow, key);
      };
      c.metrics(m + " / mean", at(*nrow, "mean"), mean_of("mean"), row_spread(*nrow, "mean"),
                row_spread(brow, "mean"));
      if (at(brow, "mean_real").is_object())  // real sequences of a synthetic scale, averaged apart
        c.metrics(m + " / mean_real", at(*nrow, "mean_real"), mean_of("mean_real"),
                  row_spread(*nrow, "mean_real"), row_spread(brow, "mean_real"));
    }
    for (const auto& bseq : arr(brow, "sequences")) {
      const std::string s = str(bseq, "sequence");
      const Json* nseq = find_by(at(*nrow, "sequences"), "sequence", s);
      if (!nseq && c.opt.subset) continue;  // not run: the subset comparison holds only what ran
      if (!nseq) {
        const Json* skip = find_by(at(fresh, "skipped_sequences"), "name", s);
        c.add("missing", true, m + " / " + s,
              "sequence missing from the new result" +
                  (skip ? " (skipped: " + str(*skip, "reason") + ")" : std::string()));
        continue;
      }
      // Tight, a one-seed run against a several-seed entry: its deterministic twin is the
      // baseline's run of the same seed, not the seeds' mean.
      if (c.rep.mode == "tight" && at(*nseq, "runs").is_null() && at(bseq, "runs").is_array()) {
        const Json* brun = run_of_seed(bseq, at(*nseq, "seed"));
        const std::string w = m + " / " + s + " / seed " + at(*nseq, "seed").dump();
        if (!brun)
          c.add("missing", true, w, "the baseline has no run of this seed (it ran seeds " +
                                        at(bseq, "seeds").dump() + ")");
        else
          c.metrics(w, merged_metrics(*nseq), merged_metrics(*brun));
        continue;
      }
      c.metrics(m + " / " + s, merged_metrics(*nseq), merged_metrics(bseq),
                Spread{&at(*nseq, "metrics_sd"), arr(*nseq, "seeds").size()},
                Spread{&at(bseq, "metrics_sd"), arr(bseq, "seeds").size()});
      // Several seeds, tight: every seed's run is a deterministic twin of the baseline's.
      if (c.rep.mode == "tight")
        for (const auto& brun : arr(bseq, "runs")) {
          const Json* nrun = nullptr;
          for (const auto& x : arr(*nseq, "runs"))
            if (at(x, "seed") == at(brun, "seed")) nrun = &x;
          const std::string w = m + " / " + s + " / seed " + at(brun, "seed").dump();
          if (!nrun)
            c.add("missing", true, w, "this seed's run is missing from the new result");
          else
            c.metrics(w, merged_metrics(*nrun), merged_metrics(brun));
        }
    }
    c.timings(m + " / timings", at(*nrow, "timings"), at(brow, "timings"), same_dev, min_reps,
              max_ratio);
  }
  for (const auto& nrow : arr(fresh, "rows"))
    if (!find_by(at(base, "rows"), "method", str(nrow, "method")))
      c.add("note", false, str(nrow, "method"), "row not in the baseline");
  if (c.opt.subset && c.rep.metrics_compared == 0)
    c.add("missing", true, "rows", "subset comparison: the new result has no row and sequence "
                                   "in common with the baseline, nothing was compared");
}

}  // namespace compare_detail

double metric_tolerance(const std::string& metric, const std::string& mode, double base) {
  const Json& tab = tolerance_table().at(mode);
  // A part without a tolerance of its own takes its metric's (tables.hpp MetricInfo::part_of).
  std::string key = metric;
  for (int depth = 0; depth < 4 && !tab.contains(key); ++depth) {
    const MetricInfo* info = metric_info(key);
    if (!info || info->part_of.empty()) break;
    key = info->part_of;
  }
  const Json& t = tab.contains(key) ? tab[key] : tab["default"];
  return t.value("abs", 0.0) + t.value("rel", 0.0) * std::fabs(base);
}

}  // namespace sgnlf::harness
