// `sgnlf compare NEW BASELINE`: compares a results JSON with a baseline (runtime/harness/
// compare.hpp); prints a readable report and exits with 4 when it finds a regression. A smoke
// result from another device is compared with that device's own baseline beside BASELINE when
// there is one (devices/<slug>/results.json, runtime/harness/device_baseline.hpp). With --equal:
// NEW must equal BASELINE field for field but times, paths and context (a merged table against
// the one-process run, results/schema.md "Cells"; runtime/harness/cells.hpp comparable_view).
#include <iostream>
#include <memory>

#include "apps/command.hpp"
#include "core/config.hpp"
#include "harness/cells.hpp"
#include "harness/compare.hpp"
#include "harness/device_baseline.hpp"

namespace sgnlf::app {
namespace {

const Registrar reg("compare", "Compare a results JSON with a baseline (exit 4 on regression)",
                    [](CLI::App& sub) {
  auto fresh = std::make_shared<std::string>();
  auto base = std::make_shared<std::string>();
  auto opt = std::make_shared<harness::CompareOptions>();
  auto no_timings = std::make_shared<bool>(false);
  auto committed_only = std::make_shared<bool>(false);
  auto equal = std::make_shared<bool>(false);
  sub.add_option("NEW", *fresh, "New results.json")->required();
  sub.add_option("BASELINE", *base, "Baseline results JSON")->required();
  auto* mode = sub.add_option("--mode", opt->mode, "auto | tight | loose")->capture_default_str();
  auto* strict = sub.add_flag("--strict", opt->strict, "Improvements beyond tolerance fail too");
  auto* no_t = sub.add_flag("--no-timings", *no_timings, "Do not compare timings");
  auto* subset = sub.add_flag("--subset", opt->subset,
               "Compare only the rows and sequences that NEW ran (a bench --rows/--sequences "
               "run against a whole table)");
  auto* reps =
      sub.add_option("--min-repetitions", opt->min_repetitions, "Timing repetitions needed");
  auto* ratio = sub.add_option("--max-ratio", opt->max_median_ratio, "Allowed median timing ratio");
  auto* own = sub.add_flag("--no-device-baseline", *committed_only,
               "A smoke result from another device: compare with BASELINE itself, not with that "
               "device's own baseline beside it (devices/<slug>/results.json)");
  sub.add_flag("--equal", *equal,
               "No tolerances: NEW must equal BASELINE (a run of the same table, options, commit "
               "and device, e.g. merged cells against the one-process run) in every field but "
               "times, paths and context (results/schema.md \"Cells\"); exit 4 listing the "
               "JSON pointers that differ")
      ->excludes(mode)->excludes(strict)->excludes(no_t)->excludes(subset)->excludes(reps)
      ->excludes(ratio)->excludes(own);
  return std::function<int()>([=] {
    if (*equal) {
      const auto diff = harness::table_differences(load_json_file(*fresh), load_json_file(*base));
      std::cout << "new:      " << *fresh << "\nbaseline: " << *base << "\n";
      if (!diff.empty()) {
        std::cout << "DIFFERENT (apart from times, paths and context) at:\n";
        for (const auto& d : diff) std::cout << "  " << d << "\n";
        return 4;
      }
      std::cout << "equal (apart from times, paths and context)\n";
      return 0;
    }
    opt->timings = !*no_timings;
    const Json fresh_json = load_json_file(*fresh);
    harness::BaselineChoice b{*base, load_json_file(*base), false, ""};
    if (!*committed_only) b = harness::choose_baseline(*base, b.baseline, fresh_json);
    harness::CompareOptions o = *opt;
    o.device_baseline = b.looked_for;
    o.device_baseline_used = b.per_device;
    const auto report = harness::compare_results(fresh_json, b.baseline, o);
    std::cout << "new:      " << *fresh << "\nbaseline: " << b.path
              << (b.per_device ? " (this device's own; committed: " + *base + ")" : std::string())
              << "\n" << harness::format_report(report);
    return report.regression() ? 4 : 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
