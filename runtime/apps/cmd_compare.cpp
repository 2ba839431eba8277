// `sgnlf compare NEW BASELINE`: compares a results JSON with a baseline (runtime/harness/
// compare.hpp); prints a readable report and exits with 4 when it finds a regression. A smoke
// result from another device is compared with that device's own baseline beside BASELINE when
// there is one (devices/<slug>/results.json, runtime/harness/device_baseline.hpp).
#include <iostream>
#include <memory>

#include "apps/command.hpp"
#include "core/config.hpp"
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
  sub.add_option("NEW", *fresh, "New results.json")->required();
  sub.add_option("BASELINE", *base, "Baseline results JSON")->required();
  sub.add_option("--mode", opt->mode, "auto | tight | loose")->capture_default_str();
  sub.add_flag("--strict", opt->strict, "Improvements beyond tolerance fail too");
  sub.add_flag("--no-timings", *no_timings, "Do not compare timings");
  sub.add_flag("--subset", opt->subset,
               "Compare only the rows and sequences that NEW ran (a bench --rows/--sequences "
               "run against a whole table)");
  sub.add_option("--min-repetitions", opt->min_repetitions, "Timing repetitions needed");
  sub.add_option("--max-ratio", opt->max_median_ratio, "Allowed median timing ratio");
  sub.add_flag("--no-device-baseline", *committed_only,
               "A smoke result from another device: compare with BASELINE itself, not with that "
               "device's own baseline beside it (devices/<slug>/results.json)");
  return std::function<int()>([=] {
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
