// Coarse waves (render.coarse_waves > 1 with early ray termination, see render_config.hpp;
// kernels/pipeline/coarse_waves.cl): the coarse pass in waves, an even split of the coarse
// samples; wave k evaluates its samples on the rays whose termination index (as
// pipeline::SampleCompaction finds it) does not lie below the wave yet. Samples not evaluated sit
// at a dead σ (zero weight). Owns the alive rays of a wave, the per-ray done flags, and the
// wave's positions and encodings.
#pragma once
#include <functional>

#include "cl/runtime.hpp"

namespace sgnlf::pipeline {

class CoarseWaves {
 public:
  // Capacity: max_rays rays of n_samples coarse samples in `waves` waves (2 ≤ waves ≤
  // n_samples); `width` floats per encoding; eps = render.stop_transmittance.
  CoarseWaves(cl::Runtime& rt, int max_rays, int n_samples, int waves, int width, float eps);

  // The field on `rows` positions x (rows × 3): encodes them into enc (rows × width), runs the
  // density MLP on them and returns its output (kDensStride floats per row).
  using Field = std::function<const cl::Buffer&(const cl::Buffer& x, int rows, cl::Buffer& enc)>;
  // The coarse pass of n_rays rays at positions x_c (n_rays × n_samples × 3): fills enc_c (the
  // encodings, width floats per sample) and h0 (σ logits, kDeadLogit where not evaluated) in the
  // coarse layout; `weights` recomputes the coarse weights w_c from h0 after each wave. One
  // blocking read of n_rays ints per wave but the last. Returns the samples evaluated.
  long run(int n_rays, const cl::Buffer& x_c, const cl::Buffer& w_c, cl::Buffer& enc_c,
           cl::Buffer& h0, const Field& field, const std::function<void()>& weights);

 private:
  int S_, waves_, width_;
  float eps_;
  cl::Kernel fill_, wave_gather_, wave_scatter_, wave_done_;
  cl::Buffer alive_, done_, x_w_, enc_w_;  // alive rays, done flags (int32); wave rows
};

}  // namespace sgnlf::pipeline
