// Roofline probes: best of a few runs of each probe kernel.
#include "probe.hpp"

#include <algorithm>
#include <vector>

#include "support/bench_support.hpp"

namespace sgnlf::bench {

const Roofline& roofline() {
  static const Roofline r = [] {
    auto& rt = runtime();
    Roofline out;
    {
      const int items = 1 << 14, iters = 4096;
      cl::Buffer sink(rt, size_t(items) * 4);
      auto k = rt.kernel("field/probe.cl", "field_probe_fma");
      k.set_args(iters, 0.999f, sink);
      double best = 1e30;
      for (int rep = 0; rep < 4; ++rep) best = std::min(best, k.launch({size_t(items)}, {64}).elapsed_ms());
      out.gflops = double(items) * iters * 256.0 / (best * 1e-3) * 1e-9;
    }
    {
      const int n4 = 1 << 23;  // 128 MiB per buffer
      cl::Buffer a(rt, size_t(n4) * 16), b(rt, size_t(n4) * 16);
      a.fill_zero();
      auto k = rt.kernel("field/probe.cl", "field_probe_copy");
      k.set_args(n4, a, b);
      double best = 1e30;
      for (int rep = 0; rep < 4; ++rep) best = std::min(best, k.launch({size_t(n4)}, {64}).elapsed_ms());
      out.gbs = double(n4) * 32.0 / (best * 1e-3) * 1e-9;
    }
    {
      const uint32_t entries = 1u << 23;  // 64 MiB of float2, far beyond the caches
      const int items = 1 << 18, per_item = 16;
      cl::Buffer table(rt, size_t(entries) * 8), sink(rt, size_t(items) * 4);
      table.fill_zero();
      auto k = rt.kernel("field/probe.cl", "field_probe_gather");
      k.set_args(per_item, entries - 1u, table, sink);
      double best = 1e30;
      for (int rep = 0; rep < 4; ++rep) best = std::min(best, k.launch({size_t(items)}, {64}).elapsed_ms());
      out.gathers = double(items) * per_item / (best * 1e-3);
    }
    return out;
  }();
  return r;
}

}  // namespace sgnlf::bench
