// Helpers shared by the field benchmarks: random inputs, wall-clock timing of enqueued passes
// (enqueue + clFinish, so launch overheads count) and the points/s, GFLOP/s, GB/s counters with
// their fraction of the roofline probes measured in the same run.
#pragma once
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <vector>

#include "core/rng.hpp"
#include "probe.hpp"
#include "support/bench_support.hpp"

namespace sgnlf::bench {

inline std::vector<float> uniform(size_t n, float lo, float hi, uint64_t seed) {
  Rng r(seed);
  std::vector<float> v(n);
  for (auto& x : v) x = r.uniform(lo, hi);
  return v;
}

// Ray-coherent sample positions (the renderer's order): `rays` rays from origins near the
// centre in random directions, `samples` evenly spaced points each, clamped to [−1, 1]³.
inline std::vector<float> ray_points(int rays, int samples, uint64_t seed) {
  Rng r(seed);
  std::vector<float> x;
  x.reserve(size_t(rays) * samples * 3);
  for (int k = 0; k < rays; ++k) {
    float o[3], d[3], len = 0;
    for (int a = 0; a < 3; ++a) {
      o[a] = r.uniform(-0.1f, 0.1f);
      d[a] = r.uniform(-1.0f, 1.0f);
      len += d[a] * d[a];
    }
    len = std::sqrt(len);
    for (int s = 0; s < samples; ++s) {
      const float t = 1.5f * float(s) / float(samples);
      for (int a = 0; a < 3; ++a) x.push_back(std::clamp(o[a] + t * d[a] / len, -1.0f, 1.0f));
    }
  }
  return x;
}

// Process CPU seconds (all threads, including the OpenCL device's worker threads).
inline double process_cpu_seconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

// Runs `pass` once to warm up, then once per iteration; returns the summed wall seconds and
// sets the counter cpu_s (process CPU seconds per iteration: robust to other load on a shared
// machine, where wall time is not).
template <typename F>
double run_timed(benchmark::State& state, F&& pass) {
  auto& rt = runtime();
  add_device_context();
  roofline();  // probes run before the timed passes, not in the middle of them
  pass();
  rt.finish();
  double total = 0;
  const double cpu0 = process_cpu_seconds();
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    pass();
    rt.finish();
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(dt);
    total += dt;
  }
  state.counters["cpu_s"] =
      (process_cpu_seconds() - cpu0) / std::max<double>(1, double(state.iterations()));
  return total;
}

// Per-iteration work: points, FLOPs, bytes (0 = not reported); `secs` from run_timed.
inline void set_counters(benchmark::State& state, double secs, double points, double flops,
                         double bytes) {
  using benchmark::Counter;
  const auto& roof = roofline();
  const double it = double(state.iterations());
  secs = std::max(secs, 1e-12);
  state.counters["points_per_s"] = Counter(points * it / secs);
  if (state.counters.count("cpu_s") && state.counters["cpu_s"].value > 0)
    state.counters["points_per_cpu_s"] = points / state.counters["cpu_s"].value;
  if (flops > 0) {
    const double g = flops * it / secs * 1e-9;
    state.counters["GFLOP/s"] = g;
    state.counters["peak_GFLOP/s"] = roof.gflops;
    state.counters["frac_peak"] = g / roof.gflops;
  }
  if (bytes > 0) {
    const double g = bytes * it / secs * 1e-9;
    state.counters["GB/s"] = g;
    state.counters["peak_GB/s"] = roof.gbs;
    state.counters["frac_peak"] = g / roof.gbs;
  }
}

}  // namespace sgnlf::bench
