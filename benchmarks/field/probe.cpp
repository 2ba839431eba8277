// Roofline for the field benchmarks: best of a few launches of the harness's probe kernels
// (runtime/harness/roofline.hpp, kernels/roofline/roofline.cl), measured in the same process.
#include "probe.hpp"

#include <algorithm>

#include "harness/roofline.hpp"
#include "support/bench_support.hpp"

namespace sgnlf::bench {

const Roofline& roofline() {
  static const Roofline r = [] {
    harness::RooflineProbe probe(runtime());
    Roofline out;
    const auto best_of = [](auto&& launch) {
      double best = 1e30;
      for (int rep = 0; rep < 4; ++rep) best = std::min(best, launch());
      return best;
    };
    {
      const size_t items = size_t(1) << 14;
      const int iters = 4096;
      probe.run_fma(items, iters);  // builds the program
      const double ms = best_of([&] { return probe.run_fma(items, iters); });
      out.gflops = harness::fma_flops(items, iters) / (ms * 1e-3) * 1e-9;
    }
    {
      const size_t floats = size_t(1) << 25;  // 128 MiB per array
      probe.alloc_stream(floats);
      const double ms = best_of([&] { return probe.run_copy(); });
      out.gbs = harness::copy_bytes(floats) / (ms * 1e-3) * 1e-9;
    }
    {
      const size_t entries = size_t(1) << 23, items = size_t(1) << 18;  // 64 MiB of float2
      probe.alloc_gather_zero(entries);
      const double ms = best_of([&] { return probe.run_gather(items); });
      out.gathers = double(items) * harness::kGatherPerItem / (ms * 1e-3);
    }
    return out;
  }();
  return r;
}

}  // namespace sgnlf::bench
