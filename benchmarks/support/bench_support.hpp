// Shared benchmark helpers: the benchmark device and the context block added to Google
// Benchmark's JSON output (the same block the table harness writes: git sha and dirty flag,
// build, machine, OpenCL strings, POCL_* environment; runtime/harness/context.hpp), and the
// device's measured roofline for reporting kernels as a fraction of it.
#pragma once
#include <benchmark/benchmark.h>

#include "cl/runtime.hpp"
#include "core/config_fwd.hpp"

namespace sgnlf::bench {

// The Runtime all benchmarks of a binary share (SGNLF_DEVICE or the default device):
// cl::shared_runtime(), released by bench_main.cpp before main returns.
cl::Runtime& runtime();

// Adds the context block as "sgnlf.*" keys to the benchmark context (once). It runs from a
// static initialiser, so the keys are in the JSON's "context" before any benchmark runs.
void add_device_context();

// The roofline measured on the benchmark device (harness::measure_roofline, ~1–2 s, once per
// binary): peak_gflops_best, triad_gbs_best, copy_gbs_best and their summaries.
const Json& measured_roofline();

// Sets GFLOP/s and GB/s counters and their fractions of the measured roofline
// (frac_peak_flops, frac_peak_bw) for `flops`/`bytes` of work per iteration (0 = none).
void set_roofline_counters(benchmark::State& state, double seconds_total, double flops,
                           double bytes);

}  // namespace sgnlf::bench
