// Spectral embedding (method.md §4.1): one Ψ training step (sample the sphere, 5 evaluations per
// sample in one batched forward, read back, loss + output gradients in double on the host,
// backward, Adam) in wall time; the host loss alone; the fusion kernel (launched directly, as
// the launcher does) in OpenCL event time.
#include <benchmark/benchmark.h>

#include "core/rng.hpp"
#include "spectral/fusion.hpp"
#include "spectral/spectral_trainer.hpp"
#include "support/bench_support.hpp"

using namespace sgnlf;
using namespace sgnlf::spectral;

static void psi_train_step(benchmark::State& state) {
  auto& rt = bench::runtime();
  SpectralTrainConfig cfg;
  cfg.batch = int(state.range(0));
  SpectralTrainer trainer(rt, cfg);
  const auto shape = make_shape(ShapeSpec::preset(ShapeKind::sphere));
  Rng rng(1);
  for (auto _ : state) {
    const double loss = trainer.step(shape->sample(rng, size_t(cfg.batch)), 1e-3);
    rt.finish();
    benchmark::DoNotOptimize(loss);
  }
  const double evals = double(kEvalsPerSample) * cfg.batch;
  state.counters["samples/s"] = benchmark::Counter(double(cfg.batch), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["evals/s"] = benchmark::Counter(evals, benchmark::Counter::kIsIterationInvariantRate);
  // Forward + backward ≈ 3× the forward multiply-adds, 2 flops each.
  const double flops = 6.0 * trainer.mlp().spec().macs_per_point() * evals;
  state.counters["GFLOP"] = benchmark::Counter(flops * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(psi_train_step)->Arg(1024)->Arg(2048)->Arg(4096)->Unit(benchmark::kMillisecond)->UseRealTime();

static void spectral_loss_host(benchmark::State& state) {
  const size_t n = size_t(state.range(0));
  const int k = 16;
  Rng rng(2);
  std::vector<float> Y(kEvalsPerSample * n * k), dY(Y.size());
  for (auto& y : Y) y = rng.uniform(-1, 1);
  SpectralLossConfig cfg;
  for (auto _ : state) benchmark::DoNotOptimize(spectral_loss(Y.data(), n, k, {}, cfg, dY.data()).loss);
  state.counters["samples/s"] = benchmark::Counter(double(n), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(spectral_loss_host)->Arg(2048)->Unit(benchmark::kMillisecond);

static void fusion_fwd_event(benchmark::State& state) {
  auto& rt = bench::runtime();
  const int n = int(state.range(0)), g = 32, k = 16;
  auto kern = rt.kernel("spectral/fusion.cl", "spectral_fusion_fwd", "-DFUSION_G=32 -DFUSION_K=16");
  cl::Buffer geo(rt, size_t(n) * g * 4), psi(rt, size_t(n) * k * 4), hyb(rt, size_t(n) * (g + k) * 4);
  geo.fill_zero();
  psi.fill_zero();
  double seconds = 0;
  for (auto _ : state) {
    kern.set_args(n, 0.5f, geo, psi, hyb);
    auto ev = kern.launch({cl::round_up(size_t(n) * (g + k), 64)}, {64});
    ev.wait();
    const double s = ev.elapsed_ms() * 1e-3;
    seconds += s;
    state.SetIterationTime(s);
  }
  const double bytes = double(n) * (2 * (g + k)) * 4.0;
  state.counters["points/s"] = benchmark::Counter(double(n), benchmark::Counter::kIsIterationInvariantRate);
  bench::set_roofline_counters(state, seconds, 0, bytes);
}
BENCHMARK(fusion_fwd_event)->Arg(1 << 18)->Unit(benchmark::kMillisecond)->UseManualTime();
