#include "harness/wiring.hpp"

#include "core/error.hpp"

#ifdef SGNLF_HARNESS_WIRED
#include "harness/prepare.hpp"
#include "metrics/evaluate.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/config/train_config.hpp"
#endif

#include <cstdio>

namespace sgnlf::harness {

#ifdef SGNLF_HARNESS_WIRED
bool hooks_wired() { return true; }

BenchHooks default_hooks() {
  BenchHooks h;
  h.implemented = [](const std::string& m) { return pipeline::method_implemented(m); };
  h.run = [](const pipeline::MethodRequest& r) { return pipeline::run_method(r); };
  h.prepare = [](const SequenceDef& s, const BenchOptions& o, const std::string& dir) {
    return prepare_sequence(s, o, dir);
  };
  h.metric_definitions = [] { return metrics::definitions(); };
  h.config_hash = [](const std::string& method, const std::string& scale) -> std::string {
    if (!pipeline::method_implemented(method)) return "";
    char b[17];
    std::snprintf(b, sizeof b, "%016llx",
                  static_cast<unsigned long long>(pipeline::resolve_config(method, scale).hash()));
    return b;
  };
  return h;
}
#else
bool hooks_wired() { return false; }

BenchHooks default_hooks() {
  BenchHooks h;
  h.implemented = [](const std::string&) { return false; };
  h.run = [](const pipeline::MethodRequest& r) -> pipeline::MethodResult {
    pipeline::MethodResult res;
    res.implemented = false;
    (void)r;
    return res;
  };
  h.prepare = [](const SequenceDef& s, const BenchOptions&, const std::string&) -> PreparedSequence {
    throw Error("bench: sequence '" + s.name +
                "' cannot be prepared: this build has no datasets/pipeline modules");
  };
  return h;
}
#endif

}  // namespace sgnlf::harness
