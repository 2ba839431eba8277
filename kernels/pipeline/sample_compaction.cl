// Early ray termination's sample compaction (pipeline module, launched by
// pipeline::SampleCompaction): the live merged samples of each ray, their rows gathered into a
// compact layout for the field, and the field's outputs expanded back into the full layout the
// renderer reads. Host references: tests/pipeline/test_sample_compaction.cpp.
#include "common/scan.clh"
#include "pipeline/stop_index.clh"

#ifndef OFFSETS_WG
#define OFFSETS_WG 256
#endif

// Early ray termination (render.stop_transmittance, instant-ngp / torch-ngp's T threshold):
// merged samples behind the point where the coarse pass's transmittance fell below eps carry
// weight below eps and are not evaluated. Per ray, with coarse weights w_c (S per ray, sorted
// t_c): j = first coarse sample after which 1 − Σ_{i≤j} w_c[i] < eps; the ray keeps its merged
// samples with t ≤ t_c[j + 2] (one more coarse bin of margin), all M when there is no such j
// or j + 2 ≥ S. Merged samples are sorted, so the live ones are a prefix of count[r].
__kernel void pipeline_live_count(const int n_rays, const int S, const int M, const float eps,
                                  __global const float* t_c, __global const float* w_c,
                                  __global const float* t, __global int* count) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const int stop = pipeline_stop_index(w_c + (size_t)r * S, S, eps);
  int c = M;
  if (stop >= 0) {
    const float t_stop = t_c[(size_t)r * S + stop];
    __global const float* tr = t + (size_t)r * M;
    c = 0;
    while (c < M && tr[c] <= t_stop) ++c;
  }
  count[r] = c;
}

// The per-ray offsets from the live counts on the device (device profile compaction: device):
// offset holds count[0..n_rays) on entry (pipeline_live_count wrote it there) and gets
// offset[r] = Σ_{q<r} count[q] for r ≤ n_rays, so offset[n_rays] is the live rows' total. One
// work-group of OFFSETS_WG; integer sums, equal to the host's prefix sum on any device.
__kernel void pipeline_offsets_scan(const int n_rays, __global int* offset) {
  __local uint part[OFFSETS_WG];
  if (get_local_id(0) == 0) offset[n_rays] = 0;
  barrier(CLK_GLOBAL_MEM_FENCE);
  group_exclusive_scan((uint)n_rays + 1u, (__global uint*)offset, part);
}

// Compact rows: for ray r and sample s < count[r] (count[r] = offset[r + 1] − offset[r]),
// out[offset[r] + s] = in[r·M + s], `width` floats per row.
__kernel void pipeline_compact_rows(const int n_rays, const int M, const int width,
                                    __global const int* offset, __global const float* in,
                                    __global float* out) {
  const int q = get_global_id(0);
  if (q >= n_rays * M) return;
  const int r = q / M, s = q - r * M;
  const int o = offset[r];
  if (s >= offset[r + 1] - o) return;
  __global const float* src = in + (size_t)q * width;
  __global float* dst = out + (size_t)(o + s) * width;
  for (int k = 0; k < width; ++k) dst[k] = src[k];
}

// The inverse for the field outputs the renderer reads: h0[q] = dens[row·dens_stride] (σ logit,
// column 0) and head[q] = head_c[row] (2 values) for live samples; dead samples get
// h0 = dead_h0 (σ = exp(dead_h0) ≈ 0: zero weight) and head = 0.
__kernel void pipeline_expand_outputs(const int n_rays, const int M, const int dens_stride,
                                      const float dead_h0, __global const int* offset,
                                      __global const float* dens, __global const float* head_c,
                                      __global float* h0, __global float* head) {
  const int q = get_global_id(0);
  if (q >= n_rays * M) return;
  const int r = q / M, s = q - r * M;
  const int o = offset[r];
  if (s < offset[r + 1] - o) {
    const size_t row = (size_t)(o + s);
    h0[q] = dens[row * dens_stride];
    head[2 * q + 0] = head_c[2 * row + 0];
    head[2 * q + 1] = head_c[2 * row + 1];
  } else {
    h0[q] = dead_h0;
    head[2 * q + 0] = 0.0f;
    head[2 * q + 1] = 0.0f;
  }
}

// ray[k] = r for the compact rows k of ray r (offset[r] ≤ k < offset[r + 1]).
__kernel void pipeline_row_ray(const int n_rays, __global const int* offset, __global int* ray) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  for (int k = offset[r]; k < offset[r + 1]; ++k) ray[k] = r;
}
