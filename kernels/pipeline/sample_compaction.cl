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

// The same counts under the gpu profile (ray_work_items > 1): RAY_WI work-items per ray,
// work-groups of RAY_WG (both set by SampleCompaction from the profile). The stop index stays
// one work-item's serial float sum (lane 0), in pipeline_stop_index's order, since it must
// equal the cpu kernel's and pipeline_wave_done's exactly; the merged samples, the longer walk
// (M per ray), are split across the lanes: lane l finds the first s ≡ l (mod RAY_WI) with
// !(t[s] ≤ t_stop), and the count is the least of the lanes' (a local min tree). Integers: the
// same count as pipeline_live_count's walk on any device, also for unsorted t.
#ifdef RAY_WI
__kernel void pipeline_live_count_wide(const int n_rays, const int S, const int M,
                                       const float eps, __global const float* t_c,
                                       __global const float* w_c, __global const float* t,
                                       __global int* count) {
  __local int stop_l[RAY_WG / RAY_WI];
  __local int first[RAY_WG];
  const int lid = get_local_id(0), lane = lid % RAY_WI, slot = lid / RAY_WI;
  const int r = get_group_id(0) * (RAY_WG / RAY_WI) + slot;
  if (lane == 0) stop_l[slot] = r < n_rays ? pipeline_stop_index(w_c + (size_t)r * S, S, eps) : -1;
  barrier(CLK_LOCAL_MEM_FENCE);
  const int stop = stop_l[slot];
  int c = M;
  if (r < n_rays && stop >= 0) {
    const float t_stop = t_c[(size_t)r * S + stop];
    __global const float* tr = t + (size_t)r * M;
    for (int s = lane; s < M; s += RAY_WI)
      if (!(tr[s] <= t_stop)) {
        c = s;
        break;
      }
  }
  first[lid] = c;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int h = RAY_WI / 2; h > 0; h >>= 1) {
    if (lane < h) first[lid] = min(first[lid], first[lid + h]);
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lane == 0 && r < n_rays) count[r] = first[lid];
}

// pipeline_row_ray with RAY_WI work-items per ray: lane l writes rows offset[r] + l,
// + l + RAY_WI, ... of ray r. The same words.
__kernel void pipeline_row_ray_wide(const int n_rays, __global const int* offset,
                                    __global int* ray) {
  const int i = get_global_id(0);
  const int r = i / RAY_WI, lane = i - r * RAY_WI;
  if (r >= n_rays) return;
  const int end = offset[r + 1];
  for (int k = offset[r] + lane; k < end; k += RAY_WI) ray[k] = r;
}
#endif

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
