// The device's measured roofline: peak FP32 FLOP/s (float16 FMA chains) and streaming
// bandwidth (copy, triad) from the kernels in kernels/roofline/roofline.cl. The harness
// records it in every result (context.roofline) and the benchmarks use it to report kernels
// as a fraction of the roofline. Sizes, flops and bytes are defined here once and shared by
// the correctness test (tests/harness) and the benchmark (benchmarks/roofline).
#pragma once
#include <cstddef>
#include <vector>

#include "cl/runtime.hpp"
#include "core/config.hpp"

namespace sgnlf::harness {

constexpr int kFmaChains = 8;   // independent accumulators per work-item
constexpr int kFmaLanes = 16;   // float16
constexpr float kFmaA = 0.999f; // x ← x·a + b converges to b / (1 − a): stays finite
constexpr float kFmaB = 0.001f;

inline double fma_flops(size_t work_items, int iters) {
  return 2.0 * kFmaChains * kFmaLanes * double(iters) * double(work_items);
}
inline double copy_bytes(size_t n_floats) { return 2.0 * 4.0 * double(n_floats); }
inline double triad_bytes(size_t n_floats) { return 3.0 * 4.0 * double(n_floats); }

class RooflineProbe {
 public:
  explicit RooflineProbe(cl::Runtime& rt);
  // One launch of work_items × iters; returns the kernel's event time in ms.
  double run_fma(size_t work_items, int iters);
  std::vector<float> fma_output(size_t work_items) const;  // after run_fma
  // Streaming arrays of n_floats (a multiple of 4) each; b = 1, c = 2 after allocation.
  void alloc_stream(size_t n_floats);
  double run_copy();   // b → a
  double run_triad(float s);  // a = b + s·c
  std::vector<float> stream_output() const;  // array a
  size_t stream_floats() const { return n_floats_; }

 private:
  cl::Runtime& rt_;
  cl::Kernel fma_, copy_, triad_;
  cl::Buffer fma_out_;
  size_t fma_items_ = 0;
  cl::Buffer a_, b_, c_;
  size_t n_floats_ = 0;
};

struct RooflineOptions {
  double target_launch_ms = 40.0;  // FMA launches are scaled to about this long
  int repetitions = 7;
  size_t stream_floats = size_t(1) << 24;  // 64 MiB per array: far beyond any cache here
  void validate() const;
};

// Measures the roofline in about 1–2 s on this machine: {peak_gflops, copy_gbs, triad_gbs}
// as repetition summaries (median/min/max), plus the probe sizes.
Json measure_roofline(cl::Runtime& rt, const RooflineOptions& opt = {});

}  // namespace sgnlf::harness
