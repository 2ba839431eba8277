// The fast renderer's ray marching (pipeline module, launched by pipeline::FastMarch): of each
// ray's samples only those in occupied cells of an occupancy grid are evaluated, front to back
// in waves until the ray's transmittance falls below a threshold; the LiDAR head runs only on
// samples whose weight exceeds a threshold. Host references: tests/pipeline/test_fast_march.cpp.

#include "pipeline/occupancy.clh"

// occ[p] = whether x[p] must be evaluated (its cell occupied, or outside the grid), for n points
// (the lookup on its own, for tests).
__kernel void pipeline_grid_lookup(const int n, const float4 lo, const float4 inv_cell,
                                   const int4 dims, __global const uchar* grid,
                                   __global const float* x, __global int* occ) {
  const int p = get_global_id(0);
  if (p >= n) return;
  occ[p] = fast_occupied(vload3(p, x), lo, inv_cell, dims, grid);
}

// Per ray r (S samples at x, ray-major): the indices of its samples in occupied cells, in order,
// idx[r·S + k] for k < count[r]; with use_known, without the samples already known
// (known[r·S + s] = 1; known is not read otherwise).
__kernel void pipeline_occupied_list(const int n_rays, const int S, const float4 lo,
                                     const float4 inv_cell, const int4 dims,
                                     __global const uchar* grid,
                                     __global const float* x, const int use_known,
                                     __global const int* known, __global int* idx,
                                     __global int* count) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  __global int* ir = idx + (size_t)r * S;
  int c = 0;
  for (int s = 0; s < S; ++s) {
    const size_t q = (size_t)r * S + s;
    if (use_known && known[q]) continue;
    if (fast_occupied(vload3(q, x), lo, inv_cell, dims, grid)) ir[c++] = s;
  }
  count[r] = c;
}

// The merged pass of importance sampling (FastMarch::merged_pass): merged sample q (ray r,
// M per ray) whose source src[q] is coarse sample s < S_c that the coarse pass evaluated (its
// logit h0_c[r·S_c + s] is not `dead`) takes that pass's logit and density row (`stride`
// floats from dens_c) and is known[q] = 1; the others (importance samples, coarse ones the
// coarse pass skipped) are known[q] = 0 and left as they are.
__kernel void pipeline_march_prefill(const int n, const int S_c, const int M, const int stride,
                                     const float dead, __global const int* src,
                                     __global const float* h0_c, __global const float* dens_c,
                                     __global float* h0, __global float* dens_full,
                                     __global int* known) {
  const int q = get_global_id(0);
  if (q >= n) return;
  const int r = q / M, s = src[q];
  int k = 0;
  if (s < S_c) {
    const size_t c = (size_t)r * S_c + s;
    const float h = h0_c[c];
    if (h != dead) {
      h0[q] = h;
      __global const float* a = dens_c + c * stride;
      __global float* b = dens_full + (size_t)q * stride;
      for (int j = 0; j < stride; ++j) b[j] = a[j];
      k = 1;
    }
  }
  known[q] = k;
}

// One wave's rows: alive ray a (ray alive[a]) takes its occupied samples cursor[a] ..
// cursor[a] + (offset[a + 1] − offset[a]) − 1; row offset[a] + k gets the position of its k-th
// and row_q[row] = the sample's index in the full layout (r·S + s).
__kernel void pipeline_march_gather(const int n_alive, const int S, const int K,
                                    __global const int* alive, __global const int* cursor,
                                    __global const int* offset, __global const int* idx,
                                    __global const float* x, __global float* x_w,
                                    __global int* row_q) {
  const int q = get_global_id(0);
  if (q >= n_alive * K) return;
  const int a = q / K, k = q - a * K;
  const int o = offset[a];
  if (k >= offset[a + 1] - o) return;
  const int r = alive[a];
  const int s = idx[(size_t)r * S + cursor[a] + k];
  const size_t full = (size_t)r * S + s;
  vstore3(vload3(full, x), o + k, x_w);
  row_q[o + k] = (int)full;
}

// The wave's density outputs into the full layout: h0[q] = σ logit (column 0 of the row) and
// the whole row (`stride` floats: σ logit and geometric features, the head's input) into
// dens_full[q·stride ..].
__kernel void pipeline_march_scatter(const int rows, const int stride, __global const int* row_q,
                                     __global const float* dens, __global float* h0,
                                     __global float* dens_full) {
  const int row = get_global_id(0);
  if (row >= rows) return;
  const size_t q = (size_t)row_q[row];
  __global const float* src = dens + (size_t)row * stride;
  h0[q] = src[0];
  __global float* dst = dens_full + q * stride;
  for (int c = 0; c < stride; ++c) dst[c] = src[c];
}

// Whether alive ray a (ray r) is done after its wave: its weights w (S per ray, full layout,
// dead samples at zero) reach 1 − Σ_{i≤j} w_i < eps at some j up to its last evaluated sample
// idx[r·S + cursor_end[a] − 1]: every sample behind j carries less than eps of weight in all.
// eps = 0: never (float sums of weights may exceed 1).
__kernel void pipeline_march_done(const int n_alive, const int S, const float eps,
                                  __global const int* alive, __global const int* cursor_end,
                                  __global const int* idx, __global const float* w,
                                  __global int* done) {
  const int a = get_global_id(0);
  if (a >= n_alive) return;
  const int r = alive[a];
  const int end = idx[(size_t)r * S + cursor_end[a] - 1];
  __global const float* wr = w + (size_t)r * S;
  float acc = 0.0f;
  int d = 0;
  for (int j = 0; j <= end && eps > 0.0f; ++j) {
    acc += wr[j];
    if (1.0f - acc < eps) {
      d = 1;
      break;
    }
  }
  done[a] = d;
}

// Head rows per ray: the samples with weight above thr (count[r] of them).
__kernel void pipeline_head_count(const int n_rays, const int S, const float thr,
                                  __global const float* w, __global int* count) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  __global const float* wr = w + (size_t)r * S;
  int c = 0;
  for (int s = 0; s < S; ++s) c += wr[s] > thr ? 1 : 0;
  count[r] = c;
}

// The head rows of ray r at offset[r] ..: their density rows (the head's input) from dens_full,
// their full-layout index into row_q and their ray into row_ray.
__kernel void pipeline_head_gather(const int n_rays, const int S, const int stride,
                                   const float thr, __global const float* w,
                                   __global const int* offset, __global const float* dens_full,
                                   __global float* dens_h, __global int* row_q,
                                   __global int* row_ray) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  __global const float* wr = w + (size_t)r * S;
  int row = offset[r];
  for (int s = 0; s < S; ++s) {
    if (!(wr[s] > thr)) continue;
    const size_t q = (size_t)r * S + s;
    for (int c = 0; c < stride; ++c) dens_h[(size_t)row * stride + c] = dens_full[q * stride + c];
    row_q[row] = (int)q;
    row_ray[row] = r;
    ++row;
  }
}

// The head's outputs (2 per row) into the full layout.
__kernel void pipeline_head_scatter(const int rows, __global const int* row_q,
                                    __global const float* head_h, __global float* head) {
  const int row = get_global_id(0);
  if (row >= rows) return;
  const size_t q = (size_t)row_q[row];
  head[2 * q + 0] = head_h[2 * row + 0];
  head[2 * q + 1] = head_h[2 * row + 1];
}

// h0 = dead logit everywhere, head logits = off logit everywhere (n samples).
__kernel void pipeline_march_fill(const int n, const float dead, const float off,
                                  __global float* h0, __global float* head) {
  const int q = get_global_id(0);
  if (q >= n) return;
  h0[q] = dead;
  head[2 * q + 0] = off;
  head[2 * q + 1] = off;
}
