// `sgnlf compare NEW BASELINE` (harness/compare.hpp): whether the two results are comparable
// at all (schema, table, scale, data), which tolerances hold (tight for deterministic twins on
// one device, driver, profile and configs; loose otherwise; a smoke table tight on its
// baseline's device or while every metric matches, else loose with a note that the device has
// no baseline of its own), then the row walk of compare_rows.cpp in that mode, and the report.
#include "harness/compare.hpp"

#include <sstream>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "harness/compare_rows.hpp"
#include "harness/device_baseline.hpp"
#include "harness/schema.hpp"
#include "harness/tables.hpp"

namespace sgnlf::harness {
namespace {

using compare_detail::arr;
using compare_detail::at;
using compare_detail::Comparer;
using compare_detail::compare_rows;
using compare_detail::find_by;
using compare_detail::run_of_seed;
using compare_detail::str;

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

int failing(const CompareReport& r) {
  int n = 0;
  for (const auto& f : r.findings) n += f.fails;
  return n;
}

std::string device_words(const Json& ctx_opencl, const Json& results) {
  const Json& profile = at(at(at(results, "context"), "device_profile"), "name");
  return "device " + at(ctx_opencl, "device").dump() + " (driver " +
         at(ctx_opencl, "driver_version").dump() +
         (profile.is_null() ? std::string() : ", profile " + profile.dump()) + ")";
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
