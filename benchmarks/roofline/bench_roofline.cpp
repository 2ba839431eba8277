// The device's roofline as Google Benchmarks (OpenCL event times): peak FP32 FLOP/s from
// float16 FMA chains and streaming bandwidth from copy and triad (kernels/roofline). The same
// kernels, sizes, flop and byte counts as harness::measure_roofline, which the table harness
// records in every result.
#include "core/config.hpp"
#include "harness/roofline.hpp"
#include "support/bench_support.hpp"

using namespace sgnlf;

static void BM_RooflineFma(benchmark::State& state) {
  auto& rt = bench::runtime();
  harness::RooflineProbe probe(rt);
  const size_t items = size_t(state.range(0));
  const int iters = int(state.range(1));
  probe.run_fma(items, iters);  // build + warm-up
  double total = 0;
  for (auto _ : state) {
    const double s = probe.run_fma(items, iters) * 1e-3;
    state.SetIterationTime(s);
    total += s;
  }
  state.counters["GFLOP/s"] = harness::fma_flops(items, iters) * double(state.iterations()) / total * 1e-9;
}
BENCHMARK(BM_RooflineFma)->Args({4096, 4096})->Args({16384, 1024})->UseManualTime()
    ->Unit(benchmark::kMillisecond);

static void BM_RooflineCopy(benchmark::State& state) {
  harness::RooflineProbe probe(bench::runtime());
  const size_t n = size_t(state.range(0));
  probe.alloc_stream(n);
  probe.run_copy();
  double total = 0;
  for (auto _ : state) {
    const double s = probe.run_copy() * 1e-3;
    state.SetIterationTime(s);
    total += s;
  }
  state.counters["GB/s"] = harness::copy_bytes(n) * double(state.iterations()) / total * 1e-9;
}
BENCHMARK(BM_RooflineCopy)->Arg(1 << 22)->Arg(1 << 24)->UseManualTime()
    ->Unit(benchmark::kMillisecond);

static void BM_RooflineTriad(benchmark::State& state) {
  harness::RooflineProbe probe(bench::runtime());
  const size_t n = size_t(state.range(0));
  probe.alloc_stream(n);
  probe.run_triad(3.0f);
  double total = 0;
  for (auto _ : state) {
    const double s = probe.run_triad(3.0f) * 1e-3;
    state.SetIterationTime(s);
    total += s;
  }
  state.counters["GB/s"] = harness::triad_bytes(n) * double(state.iterations()) / total * 1e-9;
}
BENCHMARK(BM_RooflineTriad)->Arg(1 << 22)->Arg(1 << 24)->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// The probe the harness runs (all three, ~1–2 s), reported as counters of one benchmark.
static void BM_MeasureRoofline(benchmark::State& state) {
  Json r;
  for (auto _ : state) r = harness::measure_roofline(bench::runtime());
  state.counters["peak_GFLOP/s"] = r["peak_gflops_best"].get<double>();
  state.counters["triad_GB/s"] = r["triad_gbs_best"].get<double>();
  state.counters["copy_GB/s"] = r["copy_gbs_best"].get<double>();
}
BENCHMARK(BM_MeasureRoofline)->Iterations(1)->Unit(benchmark::kSecond);
