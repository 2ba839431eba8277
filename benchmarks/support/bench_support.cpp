#include "support/bench_support.hpp"

#include <algorithm>

#include "cl/shared_runtime.hpp"
#include "core/config.hpp"
#include "harness/context.hpp"
#include "harness/roofline.hpp"

namespace sgnlf::bench {

cl::Runtime& runtime() {
  cl::Runtime& rt = cl::shared_runtime();
  add_device_context();
  return rt;
}

void add_device_context() {
  static bool done = false;
  if (done) return;
  done = true;
  try {
    const auto d = cl::select_device();
    benchmark::AddCustomContext("sgnlf_device", d.name);
    benchmark::AddCustomContext("sgnlf_platform", d.platform_name + " " + d.platform_version);
    benchmark::AddCustomContext("sgnlf_driver", d.driver_version);
    for (const auto& [k, v] : harness::flatten(harness::context_block(&d), "sgnlf"))
      benchmark::AddCustomContext(k, v);
  } catch (const std::exception& e) {
    benchmark::AddCustomContext("sgnlf_context_error", e.what());
  }
}

namespace {
// Before main(): Google Benchmark reports the context before the first benchmark runs.
const bool context_added = (add_device_context(), true);
}  // namespace

const Json& measured_roofline() {
  static const Json r = harness::measure_roofline(runtime());
  return r;
}

void set_roofline_counters(benchmark::State& state, double seconds_total, double flops,
                           double bytes) {
  const Json& roof = measured_roofline();
  const double it = double(state.iterations());
  const double s = std::max(seconds_total, 1e-12);
  if (flops > 0) {
    const double g = flops * it / s * 1e-9;
    state.counters["GFLOP/s"] = g;
    state.counters["frac_peak_flops"] = g / roof["peak_gflops_best"].get<double>();
  }
  if (bytes > 0) {
    const double g = bytes * it / s * 1e-9;
    state.counters["GB/s"] = g;
    state.counters["frac_peak_bw"] = g / roof["triad_gbs_best"].get<double>();
  }
}

}  // namespace sgnlf::bench
