// main() of every benchmark binary: Google Benchmark's own (BENCHMARK_MAIN), then the shared
// Runtime is released before main returns, not at exit (runtime/cl/shared_runtime.hpp says why).
#include <benchmark/benchmark.h>

#include "cl/shared_runtime.hpp"

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  sgnlf::cl::release_shared_runtime();
  return 0;
}
