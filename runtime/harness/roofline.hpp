// The device's measured roofline: peak FP32 FLOP/s (float16 FMA chains), streaming
// bandwidth (copy, triad) and the rate of random cache-missing reads (float2 gathers) from the
// kernels in kernels/roofline/roofline.cl. The harness
// records it in every result (context.roofline) and the benchmarks use it to report kernels
// as a fraction of the roofline. Sizes, flops and bytes are defined here once and shared by
// the correctness test (tests/harness) and the benchmark (benchmarks/roofline).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "cl/runtime.hpp"
#include "core/config_fwd.hpp"

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
constexpr int kGatherPerItem = 16;  // random reads per work-item of the gather probe
// Entry read by read k of work-item i of the gather probe (the kernel's hash, for tests).
inline uint32_t gather_entry(uint32_t i, uint32_t k, uint32_t mask) {
  return ((i * 2654435761u) ^ (k * 805459861u) ^ (k << 20)) & mask;
}

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
  // Gather table of `entries` float2 (a power of two) from host values; then each of
  // `work_items` sums kGatherPerItem random entries (gather_entry).
  void alloc_gather(const std::vector<float>& table_float2);
  void alloc_gather_zero(size_t entries);
  double run_gather(size_t work_items);
  std::vector<float> gather_output(size_t work_items) const;  // after run_gather
  size_t stream_floats() const { return n_floats_; }

 private:
  cl::Runtime& rt_;
  cl::Kernel fma_, copy_, triad_, gather_;
  cl::Buffer fma_out_;
  size_t fma_items_ = 0;
  cl::Buffer a_, b_, c_;
  size_t n_floats_ = 0;
  cl::Buffer table_, gather_out_;
  size_t table_entries_ = 0, gather_items_ = 0;
};

struct RooflineOptions {
  double target_launch_ms = 40.0;  // FMA launches are scaled to about this long
  int repetitions = 7;
  size_t stream_floats = size_t(1) << 24;  // 64 MiB per array: far beyond any cache here
  size_t gather_entries = size_t(1) << 23;  // float2 entries: 64 MiB
  size_t gather_items = size_t(1) << 18;    // × kGatherPerItem reads per launch
  void validate() const;
};

// Measures the roofline in about 1–2 s on this machine: {peak_gflops, copy_gbs, triad_gbs,
// gathers_per_s}
// as repetition summaries (median/min/max), plus the probe sizes.
Json measure_roofline(cl::Runtime& rt, const RooflineOptions& opt = {});

}  // namespace sgnlf::harness
