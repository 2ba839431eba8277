// `sgnlf compare NEW BASELINE`: checks a results JSON against a committed baseline. Quality
// metrics must agree within the tolerances of tables.json ("tolerances", documented in
// results/schema.md): tight when both runs are deterministic twins (same device, driver, device
// profile and run configs), loose otherwise. A smoke table (an untrained model) is tight on the
// baseline's own device; on another device it is compared with that device's own baseline when
// one exists (harness/device_baseline.hpp; the caller picks the file), else tight if every
// metric still matches and loose otherwise, with a note that the device differs and has no
// baseline. Its configs must always be the baseline's. A metric worse than its tolerance, a
// non-finite metric, a missing row, sequence or metric, or a timing whose median grew by more
// than the allowed ratio over enough repetitions on the same device is a regression. The
// library returns a report; the app prints it and exits with 4 on regression.
#pragma once
#include <string>
#include <vector>

#include "core/config_fwd.hpp"

namespace sgnlf::harness {

struct CompareOptions {
  std::string mode = "auto";  // auto | tight | loose
  bool strict = false;        // improvements beyond tolerance fail too (baseline is stale)
  bool timings = true;        // compare timings at all
  // Only the rows and sequences the new result ran (a `bench --rows/--sequences` run against a
  // whole table): the baseline's others are not required, and a row's mean is compared only
  // when both sides cover the same sequences.
  bool subset = false;
  int min_repetitions = -1;   // -1: tables.json tolerances.timing
  double max_median_ratio = -1;
  // Set by the caller that chose the baseline file (harness::choose_baseline): where the new
  // result's device's own smoke baseline is or would be ("" = not looked for), and whether the
  // baseline given is that one. Only named in the report.
  std::string device_baseline = "";
  bool device_baseline_used = false;
  void validate() const;
};

struct Finding {
  std::string kind;   // regression | improved | changed (no direction) | missing | timing | note
  bool fails = false; // counts as a regression
  std::string where;  // "lidar-nerf / kitti360-1538 / cd"
  std::string message;
};

struct CompareReport {
  std::string mode;  // tight | loose (resolved)
  std::string mode_reason;
  int metrics_compared = 0, timings_compared = 0, timings_skipped = 0;
  int seed_spread_used = 0;  // metrics whose allowance included the seed spread (loose)
  std::vector<Finding> findings;
  bool regression() const;
};

CompareReport compare_results(const Json& fresh, const Json& baseline,
                              const CompareOptions& opt = {});
std::string format_report(const CompareReport& r);

// Allowed difference for `metric` in `mode` at baseline value `base`: abs + rel·|base|.
double metric_tolerance(const std::string& metric, const std::string& mode, double base);

}  // namespace sgnlf::harness
