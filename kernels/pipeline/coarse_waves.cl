// Coarse waves (render.coarse_waves, pipeline module, launched by pipeline::CoarseWaves): the
// coarse pass in waves of samples, each wave evaluated on the rays that early termination has
// not stopped yet. Host references: tests/pipeline/test_coarse_waves.cpp.
#include "pipeline/stop_index.clh"

// buf[k] = value.
__kernel void pipeline_fill(const int n, const float value, __global float* buf) {
  const int k = get_global_id(0);
  if (k >= n) return;
  buf[k] = value;
}

// Coarse waves (render.coarse_waves): the rows of wave [s0, s0 + width) of the rays still
// alive. Row q = a·width + i holds coarse sample s0 + i of ray alive[a]:
// x_w[q] = x_c[alive[a]·S + s0 + i] (3 floats).
__kernel void pipeline_wave_gather(const int n_alive, const int S, const int s0, const int width,
                                   __global const int* alive, __global const float* x_c,
                                   __global float* x_w) {
  const int q = get_global_id(0);
  if (q >= n_alive * width) return;
  const int a = q / width, i = q - a * width;
  const size_t src = ((size_t)alive[a] * S + s0 + i) * 3;
  x_w[3 * (size_t)q + 0] = x_c[src + 0];
  x_w[3 * (size_t)q + 1] = x_c[src + 1];
  x_w[3 * (size_t)q + 2] = x_c[src + 2];
}

// The inverse for the wave's outputs: the encodings (lf floats per row) into the coarse
// layout (enc_c, reused by the merged pass) and the σ logit (column 0 of dens_w, dens_stride
// floats per row) into h0_c.
__kernel void pipeline_wave_scatter(const int n_alive, const int S, const int s0, const int width,
                                    const int lf, const int dens_stride,
                                    __global const int* alive, __global const float* enc_w,
                                    __global const float* dens_w, __global float* enc_c,
                                    __global float* h0_c) {
  const int q = get_global_id(0);
  if (q >= n_alive * width) return;
  const int a = q / width, i = q - a * width;
  const size_t dst = (size_t)alive[a] * S + s0 + i;
  for (int k = 0; k < lf; ++k) enc_c[dst * lf + k] = enc_w[(size_t)q * lf + k];
  h0_c[dst] = dens_w[(size_t)q * dens_stride];
}

// done[r] = 1 when ray r needs no coarse sample at or beyond `end`: its termination index
// (pipeline_stop_index, as pipeline_live_count finds it) lies below `end`. Samples
// not evaluated yet sit at a dead σ (zero weight) and move no sum, so the first j found over
// the evaluated prefix is the one the complete pass finds.
__kernel void pipeline_wave_done(const int n_rays, const int S, const int end, const float eps,
                                 __global const float* w_c, __global int* done) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const int stop = pipeline_stop_index(w_c + (size_t)r * S, S, eps);
  done[r] = stop >= 0 && stop < end ? 1 : 0;
}
