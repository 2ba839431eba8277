#include "harness/compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/config.hpp"
#include "core/json_lookup.hpp"
#include "harness/device_baseline.hpp"
#include "harness/schema.hpp"
#include "harness/stats.hpp"
#include "harness/tables.hpp"

namespace sgnlf::harness {
namespace {

// Null for a missing key or a non-object (core/json_lookup.hpp): never throws.
constexpr auto at = &member_or_null;

// Typed look-ups that never throw: a results file of another shape (hand-edited, truncated, from
// another tool) compares as missing rows and metrics instead of a JSON type_error.
std::string str(const Json& j, const std::string& k) {
  const Json& v = at(j, k);
  return v.is_string() ? v.get<std::string>() : std::string();
}
const Json& arr(const Json& j, const std::string& k) {
  static const Json empty = Json::array();
  const Json& v = at(j, k);
  return v.is_array() ? v : empty;
}

std::string fmt(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

const Json* find_by(const Json& arr, const std::string& key, const std::string& value) {
  if (!arr.is_array()) return nullptr;
  for (const auto& x : arr)
    if (str(x, key) == value) return &x;
  return nullptr;
}

Json merged_metrics(const Json& seq) {
  Json m = at(seq, "metrics").is_object() ? at(seq, "metrics") : Json::object();
  const Json& p = at(seq, "pose_metrics");
  if (p.is_object())
    for (auto it = p.begin(); it != p.end(); ++it) m[it.key()] = it.value();
  return m;
}

// A side's spread over seeds for one set of metrics: per-metric sample standard deviations
// over `n` seeds (results/schema.md "Several seeds"); n < 2 = one seed, no spread.
struct Spread {
  const Json* sd = nullptr;
  size_t n = 0;
};

struct Comparer {
  const CompareOptions& opt;
  CompareReport& rep;

  void add(const std::string& kind, bool fails, const std::string& where, const std::string& msg) {
    rep.findings.push_back({kind, fails, where, msg});
  }

  void metrics(const std::string& where, const Json& fresh, const Json& base,
               Spread fresh_spread = {}, Spread base_spread = {}) {
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

  void timings(const std::string& where, const Json& fresh, const Json& base, bool same_dev,
               int min_reps, double max_ratio) {
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
};

// The run of `seed` in a several-seed entry's runs[] (nullptr when it has none).
const Json* run_of_seed(const Json& entry, const Json& seed) {
  for (const auto& x : arr(entry, "runs"))
    if (at(x, "seed") == seed) return &x;
  return nullptr;
}

bool same_run_configs(const Json& fresh, const Json& base, bool subset) {
  for (const auto& brow : arr(base, "rows")) {
    const Json* nrow = find_by(at(fresh, "rows"), "method", str(brow, "method"));
    if (!nrow) {
      if (subset) continue;
      return false;
    }
    for (const auto& bs : arr(brow, "sequences")) {
      const Json* ns = find_by(at(*nrow, "sequences"), "sequence", str(bs, "sequence"));
      if (!ns && subset) continue;
      if (!ns) return false;
      // A one-seed run against a several-seed entry: the baseline's run of that seed.
      const Json* b = &bs;
      if (at(*ns, "runs").is_null() && at(bs, "runs").is_array()) b = run_of_seed(bs, at(*ns, "seed"));
      if (!b || at(*ns, "config_hash") != at(*b, "config_hash")) return false;
    }
  }
  return true;
}

// Which config hashes differ (for the message of a smoke comparison that is not a twin).
std::string config_differences(const Json& fresh, const Json& base) {
  std::vector<std::string> d;
  if (at(fresh, "config_hash") != at(base, "config_hash")) d.push_back("harness config_hash");
  for (const auto& brow : arr(base, "rows")) {
    const std::string m = str(brow, "method");
    const Json* nrow = find_by(at(fresh, "rows"), "method", m);
    if (!nrow) continue;  // reported as a missing row
    for (const auto& bs : arr(brow, "sequences")) {
      const std::string sq = str(bs, "sequence");
      const Json* ns = find_by(at(*nrow, "sequences"), "sequence", sq);
      if (ns && at(*ns, "config_hash") != at(bs, "config_hash"))  // a missing one is reported as such
        d.push_back(m + " / " + sq + " config_hash " + at(*ns, "config_hash").dump() + " vs " +
                    at(bs, "config_hash").dump());
    }
  }
  std::string out;
  for (size_t i = 0; i < d.size() && i < 4; ++i) out += (i ? "; " : "") + d[i];
  if (d.size() > 4) out += "; and " + std::to_string(d.size() - 4) + " more";
  return out;
}

}  // namespace

void CompareOptions::validate() const {
  if (mode != "auto" && mode != "tight" && mode != "loose")
    throw ConfigError("compare: mode '" + mode + "' is not auto|tight|loose");
}

bool CompareReport::regression() const {
  for (const auto& f : findings)
    if (f.fails) return true;
  return false;
}

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

namespace {

int failing(const CompareReport& r) {
  int n = 0;
  for (const auto& f : r.findings) n += f.fails;
  return n;
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

// Every row, sequence, seed run and timing of `base` against `fresh`, in c.rep.mode.
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

std::string device_words(const Json& ctx_opencl, const Json& results) {
  const Json& profile = at(at(at(results, "context"), "device_profile"), "name");
  return "device " + at(ctx_opencl, "device").dump() + " (driver " +
         at(ctx_opencl, "driver_version").dump() +
         (profile.is_null() ? std::string() : ", profile " + profile.dump()) + ")";
}

}  // namespace

CompareReport compare_results(const Json& fresh, const Json& base, const CompareOptions& opt) {
  opt.validate();
  CompareReport rep;
  rep.mode = "none";
  rep.mode_reason = "the results are not comparable";
  Comparer c{opt, rep};
  for (const auto* j : {&fresh, &base}) {
    if (str(*j, "schema") != kSchemaName || at(*j, "schema_version") != Json(kSchemaVersion)) {
      c.add("regression", true, j == &fresh ? "new" : "baseline",
            "not a " + std::string(kSchemaName) + " v" + std::to_string(kSchemaVersion) +
                " result (schema " + at(*j, "schema").dump() + " version " +
                at(*j, "schema_version").dump() + ")");
      return rep;
    }
  }
  for (const char* k : {"table", "scale", "data"})
    if (at(fresh, k) != at(base, k)) {
      c.add("regression", true, k, "not comparable: new " + at(fresh, k).dump() +
                                       " vs baseline " + at(base, k).dump());
      return rep;
    }

  const Json& cn = at(at(fresh, "context"), "opencl");
  const Json& cb = at(at(base, "context"), "opencl");
  // Same OpenCL device, driver and device profile (harness/device_baseline.hpp; a profile is
  // recorded since issue 54, and a result without one ran the "cpu" profile's shapes on a CPU).
  const bool same_profile = !different_profile(fresh, base);
  const bool same_dev = same_device(fresh, base);
  const bool same_cfg = at(fresh, "config_hash") == at(base, "config_hash") &&
                        same_run_configs(fresh, base, opt.subset);
  // A smoke table is a few dozen iterations of an untrained model: its metrics say little under
  // loose tolerances (a CD within ±140 % of a 60-step model), and a bit-identical rerun on the
  // same device is what guards the code. So its configs must be the baseline's, and on the
  // baseline's device (or against a baseline of the new result's own device) it is tight. On
  // another device without a baseline of its own it is tight when every metric still matches
  // (another PoCL CPU target may compute the same numbers), loose otherwise (below).
  const bool untrained = at(base, "scale") == Json("smoke");
  const bool smoke_other_device = opt.mode == "auto" && untrained && !same_dev;
  if (opt.mode == "auto" && untrained && !(same_dev && same_cfg)) {
    rep.mode = "tight";
    rep.mode_reason = same_dev ? "smoke scale: tight tolerances"
                               : "smoke scale: tight tolerances, also on another device or driver, "
                                 "while every metric matches";
    const std::string cfg_diff = same_cfg ? std::string() : config_differences(fresh, base);
    if (!cfg_diff.empty())
      c.add("not-twins", true, "config_hash",
            "the configs differ from the baseline's (" + cfg_diff +
                "); regenerate the baseline with the new configs");
  } else if (opt.mode == "auto") {
    rep.mode = same_dev && same_cfg ? "tight" : "loose";
    rep.mode_reason = !same_profile ? "different device profile"
                      : !same_dev   ? "different OpenCL device or driver"
                      : !same_cfg   ? "different harness or run configs"
                      : opt.device_baseline_used
                          ? "same device, driver and configs as this device's own baseline: "
                            "deterministic twins"
                          : "same device, driver and configs: deterministic twins";
  } else {
    rep.mode = opt.mode;
    rep.mode_reason = "chosen on the command line";
  }
  const Json& tt = tolerance_table().at("timing");
  const int min_reps = opt.min_repetitions > 0 ? opt.min_repetitions : tt.value("min_repetitions", 5);
  const double max_ratio = opt.max_median_ratio > 0 ? opt.max_median_ratio
                                                     : tt.value("max_median_ratio", 2.5);
  if (!smoke_other_device) {
    compare_rows(c, fresh, base, same_dev, min_reps, max_ratio);
  } else {
    const std::string devices = "the baseline was made on " + device_words(cb, base) +
                                ", this run on " + device_words(cn, fresh);
    // Tight first: a device that computes the same numbers is a twin.
    const int fails_before_rows = failing(rep);
    CompareReport tight = rep;
    Comparer tc{opt, tight};
    compare_rows(tc, fresh, base, same_dev, min_reps, max_ratio);
    if (failing(tight) == fails_before_rows) {
      rep = tight;
      c.add("note", false, "context / opencl",
            devices + "; every metric still matches within the tight tolerances");
    } else {
      // Another device's rounding, amplified by training, moves an untrained model's metrics:
      // without a baseline of that device only the loose tolerances mean anything (and the
      // schema, configs, rows, finite values); the tight misses are listed as notes.
      rep.mode = "loose";
      rep.mode_reason = "smoke scale on another OpenCL device, driver or device profile, "
                        "compared without a baseline of that device";
      compare_rows(c, fresh, base, same_dev, min_reps, max_ratio);
      std::vector<std::string> missed;
      for (const auto& f : tight.findings) {
        if (!f.fails || (f.kind != "regression" && f.kind != "improved")) continue;
        bool fails_loose = false;
        for (const auto& g : rep.findings) fails_loose |= g.fails && g.where == f.where;
        if (!fails_loose) missed.push_back(f.where);
      }
      std::string list;
      for (size_t i = 0; i < missed.size() && i < 5; ++i) list += (i ? ", " : "") + missed[i];
      if (missed.size() > 5) list += " and " + std::to_string(missed.size() - 5) + " more";
      if (!missed.empty())
        c.add("note", false, "tight",
              std::to_string(missed.size()) + " metric(s) within the loose tolerances but not "
              "the tight ones (this device's rounding, or a change the loose tolerances cannot "
              "see): " + list);
      const std::string own =
          opt.device_baseline.empty()
              ? std::string("no baseline of this device was given, so this smoke table was "
                            "compared loosely; a device's own baseline goes to "
                            "devices/<device slug>/results.json beside the committed one "
                            "(results/README.md)")
              : "no baseline of this device exists, so this smoke table was compared loosely; "
                "to hold this device to tight tolerances, copy this run's results.json to " +
                    opt.device_baseline + " (results/README.md)";
      c.add("note", false, "context / opencl", "the device differs: " + devices + ", and " + own);
    }
  }
  if (opt.device_baseline_used)
    c.add("note", false, "baseline",
          "this device's own baseline (" + opt.device_baseline +
              "), not the committed one made on another device");
  if (!same_dev)
    c.add("note", false, "timings",
          same_profile ? "not compared: different OpenCL device or driver"
                       : "not compared: different device profile");
  return rep;
}

std::string format_report(const CompareReport& r) {
  std::ostringstream o;
  int fails = 0;
  for (const auto& f : r.findings) fails += f.fails;
  o << "compare: " << r.mode << " tolerances (" << r.mode_reason << "); " << r.metrics_compared
    << " metrics and " << r.timings_compared << " timings compared, " << r.timings_skipped
    << " timings skipped (too few repetitions or another device)";
  if (r.seed_spread_used)
    o << "; " << r.seed_spread_used << " metrics allowed their seed spread (several seeds)";
  o << "\n";
  for (const auto& f : r.findings)
    o << (f.fails ? "  FAIL " : "  ok   ") << f.kind << ": " << f.where << ": " << f.message << "\n";
  o << (fails ? "REGRESSION: " + std::to_string(fails) + " finding(s) fail\n"
              : std::string("PASS: no regression\n"));
  return o.str();
}

}  // namespace sgnlf::harness
