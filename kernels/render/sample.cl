// LiDAR ray sampling (method.md §0): stratified uniform samples with Philox jitter, and
// importance samples drawn by inverse CDF from a coarse pass's weights, merged sorted with the
// coarse ones. Rays are given as origins o and unit directions d (n_rays x 3, normalised
// scene frame, protocol §2); samples are ray-major (ray r owns r*S .. r*S+S-1); positions
// x = o + t*d are point-major (N x 3). Host references: tests/render/render_reference.hpp.
#include "common/philox.clh"

// Philox streams of this file (seed, stream, index = step << 32 | counter).
#define RENDER_STREAM_UNIFORM 0x52454e31u
#define RENDER_STREAM_IMPORTANCE 0x52454e32u

inline float render_jitter(uint seed_lo, uint seed_hi, uint stream, uint step, uint counter) {
  const ulong index = ((ulong)step << 32) | (ulong)counter;
  return philox_unit(philox_block(seed_lo, seed_hi, stream, index).x);
}

inline void render_store_point(__global const float* o, __global const float* d, int r, float t,
                               int s, __global float* x) {
  x[3 * s + 0] = o[3 * r + 0] + t * d[3 * r + 0];
  x[3 * s + 1] = o[3 * r + 1] + t * d[3 * r + 1];
  x[3 * s + 2] = o[3 * r + 2] + t * d[3 * r + 2];
}

// t = near + (i + xi) * (far - near) / S, xi from Philox when jitter != 0, else 0.5 (bin
// midpoints, used for evaluation). One work-item g per quad of samples i = 4k .. 4k+3 of ray
// r, g = r * ceil(S / 4) + k; sample i uses word i % 4 of Philox block (step << 32 | g) of
// RENDER_STREAM_UNIFORM. Loop- and array-free float4 code (PoCL vectorises it), one integer
// division per quad.
inline void render_uniform_one(int r, int i, int s, float near, float bin, uint bits,
                               __global const float* o, __global const float* d,
                               __global float* t_out, __global float* x_out) {
  const float t = near + ((float)i + philox_unit(bits)) * bin;
  t_out[s] = t;
  render_store_point(o, d, r, t, s, x_out);
}

__kernel void render_sample_uniform(const int n_rays, const int n_samples, const float near,
                                    const float far, const int jitter, const uint seed_lo,
                                    const uint seed_hi, const uint step, __global const float* o,
                                    __global const float* d, __global float* t_out,
                                    __global float* x_out) {
  const int g = get_global_id(0);
  const int n_quads = (n_samples + 3) / 4;
  if (g >= n_rays * n_quads) return;
  const int r = g / n_quads, i = 4 * (g - r * n_quads), s = r * n_samples + i;
  const uint4 bits =
      jitter ? philox_block(seed_lo, seed_hi, RENDER_STREAM_UNIFORM, ((ulong)step << 32) | (ulong)g)
             : (uint4)(0x80000000u);  // philox_unit -> 0.5
  const float bin = (far - near) / (float)n_samples;
  if (i + 3 >= n_samples) {  // the ray's last, partial quad
    render_uniform_one(r, i, s, near, bin, bits.x, o, d, t_out, x_out);
    if (i + 1 < n_samples)
      render_uniform_one(r, i + 1, s + 1, near, bin, bits.y, o, d, t_out, x_out);
    if (i + 2 < n_samples)
      render_uniform_one(r, i + 2, s + 2, near, bin, bits.z, o, d, t_out, x_out);
    return;
  }
  const float4 t4 =
      near +
      ((float4)(i, i + 1, i + 2, i + 3) + convert_float4(bits >> 8) * (1.0f / 16777216.0f)) * bin;
  vstore4(t4, 0, t_out + s);
  const float3 o3 = vload3(r, o), d3 = vload3(r, d);
  const float3 x0 = o3 + t4.x * d3, x1 = o3 + t4.y * d3, x2 = o3 + t4.z * d3, x3 = o3 + t4.w * d3;
  __global float* x = x_out + 3 * s;
  vstore4((float4)(x0, x1.x), 0, x);
  vstore4((float4)(x1.y, x1.z, x2.x, x2.y), 0, x + 4);
  vstore4((float4)(x2.z, x3), 0, x + 8);
}

// One work-item per ray. The coarse samples t_c (S_c, sorted) define bins with edges
// e_0 = near, e_k = (t_{k-1} + t_k)/2, e_{S_c} = far; bin k has probability proportional to
// w_k + 1e-5 (NeRF's floor keeps empty rays sampled uniformly). Fine sample j uses
// u_j = (j + xi_j) / S_f (xi from Philox, or 0.5), so the fine samples come out sorted and one
// walk over the bins inverts the CDF; they are merged with the coarse samples on the fly
// (ties: coarse first). Output: S_c + S_f sorted samples per ray, and for each its source
// src = k for coarse sample k, S_c + j for fine sample j (lets a caller reuse what it computed
// at the coarse samples).
__kernel void render_sample_importance(const int n_rays, const int n_coarse, const int n_fine,
                                       const float near, const float far, const int jitter,
                                       const uint seed_lo, const uint seed_hi, const uint step,
                                       __global const float* o, __global const float* d,
                                       __global const float* t_coarse,
                                       __global const float* w_coarse, __global float* t_out,
                                       __global float* x_out, __global int* src_out) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const int cbase = r * n_coarse, obase = r * (n_coarse + n_fine);
  float total = 0.0f;
  for (int k = 0; k < n_coarse; ++k) total += w_coarse[cbase + k] + 1e-5f;
  const float inv_total = 1.0f / total;

  // Inverse-CDF walk state: bin k, its edges, its probability and the CDF below it.
  int k = 0;
  float cdf_lo = 0.0f;
  float p_k = (w_coarse[cbase] + 1e-5f) * inv_total;
  float e_lo = near;
  float e_hi = n_coarse > 1 ? 0.5f * (t_coarse[cbase] + t_coarse[cbase + 1]) : far;

  int ic = 0, j = 0, need_fine = 1;
  float t_fine = 0.0f;
  for (int out = 0; out < n_coarse + n_fine; ++out) {
    if (j < n_fine && need_fine) {
      need_fine = 0;
      const float xi = jitter ? render_jitter(seed_lo, seed_hi, RENDER_STREAM_IMPORTANCE, step,
                                              (uint)(r * n_fine + j))
                              : 0.5f;
      const float u = ((float)j + xi) / (float)n_fine;
      while (k < n_coarse - 1 && cdf_lo + p_k <= u) {
        cdf_lo += p_k;
        ++k;
        p_k = (w_coarse[cbase + k] + 1e-5f) * inv_total;
        e_lo = e_hi;
        e_hi = k < n_coarse - 1 ? 0.5f * (t_coarse[cbase + k] + t_coarse[cbase + k + 1]) : far;
      }
      const float f = clamp((u - cdf_lo) / p_k, 0.0f, 1.0f);
      t_fine = e_lo + f * (e_hi - e_lo);
    }
    const int take_coarse = ic < n_coarse && (j >= n_fine || t_coarse[cbase + ic] <= t_fine);
    float t;
    if (take_coarse) {
      t = t_coarse[cbase + ic];
      src_out[obase + out] = ic;
      ++ic;
    } else {
      t = t_fine;
      src_out[obase + out] = n_coarse + j;
      ++j;
      need_fine = 1;
    }
    t_out[obase + out] = t;
    render_store_point(o, d, r, t, obase + out, x_out);
  }
}

// render_sample_importance under the gpu profile (ray_work_items > 1): RAY_WI work-items per
// ray, RAY_WG per work-group (RaySampler sets both), one work-item per output sample in three
// passes over local memory (`lm`: per ray n_coarse + 1 CDF words, then n_fine fine samples):
//  1. the CDF: each lane sums a contiguous chunk of the bins' w_k + 1e-5 in order, lane 0 scans
//     the chunk sums in order, each lane rewrites its chunk as running sums from its offset;
//     cdf[m] = Σ_{k<m} (w_k + 1e-5) / total. Every word is a float sum of positive terms
//     continued from the one before it (within a chunk, or a chunk's offset, which is the
//     previous chunk's offset plus its whole sum), so the CDF never decreases;
//  2. fine sample j (u_j as in the per-ray kernel): its bin k = #{1 ≤ m < n_coarse : cdf[m] ≤ u}
//     by binary search, where the per-ray walk stops (it advances while cdf_lo + p_k ≤ u), then
//     the same interpolation, capped at the bin's upper edge (the walk's value can pass it by
//     an ulp); with sorted coarse samples the fine ones then never decrease;
//  3. the merge: coarse sample i goes to i + #{j : t_f[j] < t_c[i]}, fine sample j to
//     j + #{i : t_c[i] ≤ t_f[j]} (ties: coarse first, as the walk), both by binary search.
// The CDF's sums are in another order than the walk's running sum, so a fine sample differs
// from the per-ray kernel's by the CDF's rounding (a few ulp of 1) over its bin's probability,
// times the bin's width (tests/render/test_sampler_wide.cpp). The coarse samples must be
// sorted per ray (every caller's are: uniform or surface samples); deterministic per device.
#ifdef RAY_WI
inline int render_count_le(__local const float* v, int n, float x) {  // #{i : v[i] <= x}
  int lo = 0, hi = n;
  while (lo < hi) {
    const int mid = (lo + hi) >> 1;
    if (v[mid] <= x) lo = mid + 1; else hi = mid;
  }
  return lo;
}
inline int render_count_lt(__local const float* v, int n, float x) {  // #{i : v[i] < x}
  int lo = 0, hi = n;
  while (lo < hi) {
    const int mid = (lo + hi) >> 1;
    if (v[mid] < x) lo = mid + 1; else hi = mid;
  }
  return lo;
}
inline int render_count_le_global(__global const float* v, int n, float x) {
  int lo = 0, hi = n;
  while (lo < hi) {
    const int mid = (lo + hi) >> 1;
    if (v[mid] <= x) lo = mid + 1; else hi = mid;
  }
  return lo;
}

__kernel void render_sample_importance_wide(
    const int n_rays, const int n_coarse, const int n_fine, const float near, const float far,
    const int jitter, const uint seed_lo, const uint seed_hi, const uint step,
    __global const float* o, __global const float* d, __global const float* t_coarse,
    __global const float* w_coarse, __global float* t_out, __global float* x_out,
    __global int* src_out, __local float* lm) {
  __local float chunk_off[RAY_WG];
  const int lid = get_local_id(0), lane = lid % RAY_WI, slot = lid / RAY_WI;
  const int r = get_group_id(0) * (RAY_WG / RAY_WI) + slot;
  const int live = r < n_rays;
  __local float* cdf = lm + slot * (n_coarse + 1 + n_fine);
  __local float* fine = cdf + n_coarse + 1;
  __global const float* tc = t_coarse + (size_t)(live ? r : 0) * n_coarse;
  __global const float* wc = w_coarse + (size_t)(live ? r : 0) * n_coarse;
  // 1. The CDF, chunk by chunk.
  const int per = (n_coarse + RAY_WI - 1) / RAY_WI;
  const int lo = min(n_coarse, lane * per), hi = min(n_coarse, lo + per);
  float s = 0.0f;
  if (live)
    for (int k = lo; k < hi; ++k) s += wc[k] + 1e-5f;
  chunk_off[lid] = s;
  barrier(CLK_LOCAL_MEM_FENCE);
  if (lane == 0) {
    float acc = 0.0f;
    for (int c = 0; c < RAY_WI; ++c) {
      const float v = chunk_off[lid + c];
      chunk_off[lid + c] = acc;
      acc += v;
    }
    cdf[n_coarse] = acc;  // the total
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  const float total = cdf[n_coarse];
  const float inv_total = 1.0f / total;
  float run = chunk_off[lid];
  for (int k = lo; k < hi; ++k) {
    cdf[k] = run * inv_total;
    if (live) run += wc[k] + 1e-5f;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  // 2. The fine samples.
  if (live)
    for (int j = lane; j < n_fine; j += RAY_WI) {
      const float xi = jitter ? render_jitter(seed_lo, seed_hi, RENDER_STREAM_IMPORTANCE, step,
                                              (uint)(r * n_fine + j))
                              : 0.5f;
      const float u = ((float)j + xi) / (float)n_fine;
      const int k = render_count_le(cdf + 1, n_coarse - 1, u);
      const float p_k = (wc[k] + 1e-5f) * inv_total;
      const float e_lo = k > 0 ? 0.5f * (tc[k - 1] + tc[k]) : near;
      const float e_hi = k < n_coarse - 1 ? 0.5f * (tc[k] + tc[k + 1]) : far;
      const float f = clamp((u - cdf[k]) / p_k, 0.0f, 1.0f);
      fine[j] = fmin(e_lo + f * (e_hi - e_lo), e_hi);
    }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (!live) return;
  // 3. The merge.
  const int obase = r * (n_coarse + n_fine);
  for (int i = lane; i < n_coarse; i += RAY_WI) {
    const float t = tc[i];
    const int out = obase + i + render_count_lt(fine, n_fine, t);
    t_out[out] = t;
    src_out[out] = i;
    render_store_point(o, d, r, t, out, x_out);
  }
  for (int j = lane; j < n_fine; j += RAY_WI) {
    const float t = fine[j];
    const int out = obase + j + render_count_le_global(tc, n_coarse, t);
    t_out[out] = t;
    src_out[out] = n_coarse + j;
    render_store_point(o, d, r, t, out, x_out);
  }
}
#endif

// The clamp of sample positions to the normalised scene box [-bound, bound]^3 (LiDAR-NeRF /
// torch-ngp clamp xyzs to the aabb), applied by pipeline::LidarNerfModel to every sample set:
// x[k] = clamp(x[k], -bound, bound) for k < n (n = 3 x points), in place.
__kernel void render_clamp_points(const int n, const float bound, __global float* x) {
  const int k = get_global_id(0);
  if (k >= n) return;
  x[k] = clamp(x[k], -bound, bound);
}
