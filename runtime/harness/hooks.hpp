// What the table runner is given to do its work: preparing a sequence and running a method
// (injected, so the runner is testable without the pipeline; wiring.hpp has the app's).
#pragma once
#include <functional>
#include <string>

#include "harness/bench_options.hpp"
#include "pipeline/run/method.hpp"

namespace sgnlf::harness {

// A sequence ready on disk: the folder the pipeline reads and a description of it
// (name, source, frames, split, sensor, seed... see results/schema.md "dataset").
struct PreparedSequence {
  std::string dataset_dir;
  Json dataset = Json::object();
  Json overrides = Json::object();  // merged into MethodRequest::overrides (e.g. window)
  double seconds = 0.0;             // time spent preparing (simulation / loading)
};

struct BenchHooks {
  std::function<bool(const std::string& method)> implemented;
  std::function<pipeline::MethodResult(const pipeline::MethodRequest&)> run;
  // For a real sequence of a synthetic scale (`real_dir`), the runner passes options whose
  // data_root is the resolved folder, so the hook loads it like a --data-root window.
  std::function<PreparedSequence(const SequenceDef&, const BenchOptions&,
                                 const std::string& dir)> prepare;
  // What the metrics mean (metrics::definitions()), recorded as "metric_definitions".
  std::function<Json()> metric_definitions;
  // The resolved config hash a method's run at a scale has in this build (16 hex digits, as
  // rows[].sequences[].config_hash; tests/pipeline/config_hashes.json), "" when unknown. Used
  // by `sgnlf merge` of results tables to flag runs made with another config as stale.
  std::function<std::string(const std::string& method, const std::string& scale)> config_hash;
};

}  // namespace sgnlf::harness
