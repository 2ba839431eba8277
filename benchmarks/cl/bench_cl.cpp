// Runtime overheads: kernel launch latency and host<->device transfer bandwidth.
#include "support/bench_support.hpp"

#include <vector>

using namespace sgnlf;

static void BM_KernelLaunch(benchmark::State& state) {
  auto& rt = bench::runtime();
  const int n = 256;
  std::vector<float> x(n, 1.f);
  auto bx = cl::Buffer::from(rt, x), by = cl::Buffer::from(rt, x);
  auto k = rt.kernel("common/smoke.cl", "common_saxpy_fwd");
  k.set_args(n, 1.0f, bx, by);
  k.launch({size_t(n)}).wait();
  for (auto _ : state) k.launch({size_t(n)}).wait();
}
BENCHMARK(BM_KernelLaunch)->Unit(benchmark::kMicrosecond);

static void BM_SaxpyBandwidth(benchmark::State& state) {
  auto& rt = bench::runtime();
  const int n = int(state.range(0));
  std::vector<float> x(n, 1.f);
  auto bx = cl::Buffer::from(rt, x), by = cl::Buffer::from(rt, x);
  auto k = rt.kernel("common/smoke.cl", "common_saxpy_fwd");
  k.set_args(n, 1.0f, bx, by);
  k.launch({size_t(n)}).wait();
  for (auto _ : state) state.SetIterationTime(k.launch({size_t(n)}).elapsed_ms() * 1e-3);
  state.SetBytesProcessed(int64_t(state.iterations()) * n * 12);
}
BENCHMARK(BM_SaxpyBandwidth)->Arg(1 << 24)->UseManualTime()->Unit(benchmark::kMillisecond);
