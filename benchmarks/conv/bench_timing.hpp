// Shared by the conv-stack benchmarks (bench_conv.cpp, bench_unet.cpp): random inputs and the
// timing of enqueued passes (a warm-up pass, then one pass + clFinish per iteration, so launch
// overheads count; the device's roofline probes run before the timed passes).
#pragma once
#include <algorithm>
#include <chrono>
#include <ctime>
#include <vector>

#include "core/rng.hpp"
#include "support/bench_support.hpp"

namespace sgnlf::bench {

inline std::vector<float> uniform(size_t n, float lo, float hi, uint64_t seed) {
  Rng r(seed);
  std::vector<float> v(n);
  for (auto& x : v) x = r.uniform(lo, hi);
  return v;
}

// Returns the summed wall seconds of the timed passes; sets cpu_s (process CPU seconds per
// iteration).
template <typename F>
double run_timed(benchmark::State& state, F&& pass) {
  auto& rt = runtime();
  measured_roofline();
  pass();
  rt.finish();
  double total = 0;
  const std::clock_t cpu0 = std::clock();
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    pass();
    rt.finish();
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(dt);
    total += dt;
  }
  state.counters["cpu_s"] = double(std::clock() - cpu0) / CLOCKS_PER_SEC /
                            std::max<double>(1, double(state.iterations()));
  return total;
}

}  // namespace sgnlf::bench
