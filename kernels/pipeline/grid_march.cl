// The fast renderer's marching with samples placed by the occupancy grid (pipeline module,
// launched by pipeline::GridMarch; render::FastRenderConfig layout "march"). Host references:
// tests/pipeline/grid_march_reference.hpp.
//
// The lattice. Ray r's candidate samples are t_k = near + (k + 0.5)·h, k = 0 .. K − 1 (h the
// fine step, K = S·m: h is the protocol's bin (far − near)/S divided by m, so with m = 1 the
// lattice is the protocol's evaluation samples). The walk from k, at x = clamp(o + t_k d):
//   - outside the grid's box (or clamped): evaluate, δ = m·h, k += m (the protocol's spacing);
//   - in an occupied cell: evaluate, δ = h, k += 1;
//   - in a free cell: jump to the first lattice point past the cell's exit along the ray.
// A sample stands for [t_k, t_k + δ), as in render_volume_fwd (δ = the distance to the next
// lattice point visited; a free cell after it keeps zero density, as FastMarch's dead samples).
// Occupied cells are walked coarsely too (δ = mc·h, k += mc, mc = `coarse` bins in fine steps)
// while the ray is in coarse mode: the first coarse sample in an occupied cell whose
// α = 1 − exp(−σδ) reaches hit_alpha is not composited; the ray rewinds to k_hit − (mc − 1) (at
// least one past its last composited sample) and walks the fine lattice (δ = h, k += 1) until
// mc fine samples in a row stay below hit_alpha, then coarse again. The coarse sample before the
// hit, composited with δ = mc·h, then overlaps the first mc − 1 fine ones: optical depth of at
// most hit_alpha counted twice. hit_alpha = 0 walks every occupied cell finely.
// Rays march in waves of up to K_w samples; after each wave the rays whose transmittance fell
// below eps stop (and the rows after a hit in its wave are dropped). Sequential sums in sample
// order per ray: deterministic.

#include "pipeline/occupancy.clh"

// The walk's parameters: near, h, m, K (lattice size), bound (the scene box's clamp), mc (the
// coarse mode's step in occupied cells, in fine steps: `coarse` bins, coarse·m).
typedef struct {
  float near, h, bound;
  int m, K, mc;
} gm_lattice;

// Whether |x| ≤ bound on every axis (else the clamp moves it: evaluated as outside the box).
inline int gm_inside_bound(const float3 x, const float bound) {
  return fabs(x.x) <= bound && fabs(x.y) <= bound && fabs(x.z) <= bound;
}

// One step of the walk at lattice point *k of ray (o, d): returns 1 with the sample's t, δ and
// clamped position when k is evaluated (then *k moves past it), 0 when k lies in a free cell
// (then *k jumps past that cell).
// `fine`: the ray's mode (occupied cells at the fine spacing); *in_cell = whether the sample
// lies in an occupied cell (not outside the box).
inline int gm_step(int* k, const int fine, const float3 o, const float3 d, const gm_lattice L,
                   const float4 lo, const float4 inv_cell, const int4 dims,
                   __global const uchar* grid, float* t_out, float* dt_out, float3* x_out,
                   int* in_cell) {
  const float t = L.near + ((float)(*k) + 0.5f) * L.h;
  const float3 x = o + t * d;
  const int c = gm_inside_bound(x, L.bound) ? fast_cell(x, lo, inv_cell, dims) : -1;
  if (c >= 0 && !grid[c]) {
    // The exit of cell c along the ray: the nearest of the three far faces.
    const int i = c % dims.x, j = (c / dims.x) % dims.y, l = c / (dims.x * dims.y);
    const float3 cell = 1.0f / inv_cell.xyz;
    const float3 a = lo.xyz + (float3)((float)i, (float)j, (float)l) * cell;
    float t_exit = INFINITY;
    if (d.x != 0.0f) t_exit = fmin(t_exit, ((d.x > 0.0f ? a.x + cell.x : a.x) - o.x) / d.x);
    if (d.y != 0.0f) t_exit = fmin(t_exit, ((d.y > 0.0f ? a.y + cell.y : a.y) - o.y) / d.y);
    if (d.z != 0.0f) t_exit = fmin(t_exit, ((d.z > 0.0f ? a.z + cell.z : a.z) - o.z) / d.z);
    // The first lattice point strictly past the exit (at least the next one).
    const float kf = floor((t_exit - L.near) / L.h - 0.5f) + 1.0f;
    *k = kf > (float)(*k) ? (kf < (float)L.K ? (int)kf : L.K) : *k + 1;
    return 0;
  }
  const int step = c < 0 ? L.m : fine ? 1 : L.mc;
  *in_cell = c >= 0;
  *t_out = t;
  *dt_out = (float)step * L.h;
  *x_out = clamp(x, -L.bound, L.bound);
  *k += step;
  return 1;
}

// Per ray: the cursor at the lattice's start, transmittance 1, sums 0, no median yet; `mode`
// fine when start_fine (hit_alpha = 0 or mc = 1), else coarse; no fine sample yet (quiet), no
// composited sample (last_k = −1).
__kernel void pipeline_gm_init(const int n_rays, const int start_fine, __global int* cursor,
                               __global float* trans, __global float* acc,
                               __global float* median, __global int* mode, __global int* quiet,
                               __global int* last_k, __global int* stats) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  cursor[r] = 0;
  mode[r] = start_fine;
  quiet[r] = 0;
  stats[4 * r + 0] = 0;
  stats[4 * r + 1] = 0;
  stats[4 * r + 2] = 0;
  stats[4 * r + 3] = 0;
  last_k[r] = -1;
  trans[r] = 1.0f;
  acc[3 * r + 0] = 0.0f;
  acc[3 * r + 1] = 0.0f;
  acc[3 * r + 2] = 0.0f;
  median[r] = -1.0f;
}

// Per alive ray a (ray alive[a]) not done: count[a] = the samples its next wave takes (up to
// K_w, fewer at the lattice's end), without moving the cursor; 0 for a done ray (done given:
// use_done = 1) or at the end.
__kernel void pipeline_gm_count(const int n_alive, const int K_w, const float near, const float h,
                                const int m, const int K, const int mc, const float bound,
                                const float4 lo,
                                const float4 inv_cell, const int4 dims, __global const uchar* grid,
                                __global const int* alive, __global const float* o,
                                __global const float* d, __global const int* cursor,
                                __global const int* mode, const int use_done,
                                __global const int* done, __global int* count) {
  const int a = get_global_id(0);
  if (a >= n_alive) return;
  const int r = alive[a];
  int c = 0;
  if (!(use_done && done[a])) {
    const gm_lattice L = {near, h, bound, m, K, mc};
    const float3 o3 = vload3(r, o), d3 = vload3(r, d);
    const int fine = mode[r];
    int k = cursor[r], in_cell;
    float t, dt;
    float3 x;
    while (k < K && c < K_w)
      if (gm_step(&k, fine, o3, d3, L, lo, inv_cell, dims, grid, &t, &dt, &x, &in_cell)) ++c;
  }
  count[a] = c;
}

// The wave's rows: alive ray a writes its samples (offset[a + 1] − offset[a] of them, as
// pipeline_gm_count counted) at rows offset[a] ..: position x_w (clamped), t_w, dt_w, lattice
// index k_w, whether in an occupied cell (cell_w); and moves its cursor past them.
__kernel void pipeline_gm_emit(const int n_alive, const float near, const float h, const int m,
                               const int K, const int mc, const float bound, const float4 lo,
                               const float4 inv_cell, const int4 dims, __global const uchar* grid,
                               __global const int* alive, __global const float* o,
                               __global const float* d, __global int* cursor,
                               __global const int* mode, __global const int* offset,
                               __global float* x_w, __global float* t_w, __global float* dt_w,
                               __global int* k_w, __global int* cell_w) {
  const int a = get_global_id(0);
  if (a >= n_alive) return;
  const int r = alive[a];
  const gm_lattice L = {near, h, bound, m, K, mc};
  const float3 o3 = vload3(r, o), d3 = vload3(r, d);
  const int fine = mode[r];
  int k = cursor[r], row = offset[a], in_cell;
  const int end = offset[a + 1];
  float t, dt;
  float3 x;
  while (row < end && k < K) {
    const int k0 = k;
    if (gm_step(&k, fine, o3, d3, L, lo, inv_cell, dims, grid, &t, &dt, &x, &in_cell)) {
      vstore3(x, row, x_w);
      t_w[row] = t;
      dt_w[row] = dt;
      k_w[row] = k0;
      cell_w[row] = in_cell;
      ++row;
    }
  }
  cursor[r] = k;
}

// Compositing of the wave, alive ray a over its rows in order (σ logit in column 0 of each
// density row, `stride` floats): e = exp(−exp(min(h0, 80))·δ), w = T·(1 − e), T ← T·e (the
// arithmetic of render_volume_fwd); acc[3 r] += w·t; the median (render_median_depth's
// crossing) where the accumulated weight first reaches 1/2; w_w[row] = w; hcount[a] = rows with
// w > thr; done[a] = T < eps (eps = 0: never). In coarse mode a row in an occupied cell with
// 1 − e ≥ hit_alpha (mc > 1) is a hit: it and the wave's later rows get w = 0 (not composited,
// no head), the cursor rewinds and the mode turns fine (see the top of this file); in fine
// mode mc rows in a row below hit_alpha turn it coarse again after the wave. stats[4 r ..]
// counts the ray's composited rows in occupied cells at the coarse and at the fine spacing,
// outside the box, and its dropped rows.
__kernel void pipeline_gm_composite(const int n_alive, const int stride, const float eps,
                                    const float thr, const float hit_alpha, const int mc,
                                    __global const int* alive, __global const int* offset,
                                    __global const float* dens, __global const float* t_w,
                                    __global const float* dt_w, __global const int* k_w,
                                    __global const int* cell_w, __global float* trans,
                                    __global float* acc, __global float* median,
                                    __global int* cursor, __global int* mode,
                                    __global int* quiet, __global int* last_k,
                                    __global float* w_w, __global int* hcount,
                                    __global int* done, __global int* stats) {
  const int a = get_global_id(0);
  if (a >= n_alive) return;
  const int r = alive[a];
  float T = trans[r], depth = acc[3 * r], med = median[r];
  int hc = 0, fine = mode[r], q = quiet[r], lk = last_k[r];
  const int end = offset[a + 1], emitted_fine = fine;
  __global int* st = stats + 4 * r;
  for (int row = offset[a]; row < end; ++row) {
    const float e = exp(-exp(fmin(dens[(size_t)row * stride], 80.0f)) * dt_w[row]);
    if (!fine && mc > 1 && cell_w[row] && 1.0f - e >= hit_alpha) {
      // A hit: rewind to the fine lattice just behind it; this row and the later ones drop.
      cursor[r] = max(k_w[row] - (mc - 1), lk + 1);
      fine = 1;
      q = 0;
      for (int z = row; z < end; ++z) w_w[z] = 0.0f;
      st[3] += end - row;
      break;
    }
    if (fine) q = 1.0f - e < hit_alpha ? q + 1 : 0;
    lk = k_w[row];
    st[!cell_w[row] ? 2 : emitted_fine ? 1 : 0] += 1;
    const float w = T * (1.0f - e);
    if (med < 0.0f && (1.0f - T) + w >= 0.5f) {
      const float alpha = fmin(w / fmax(T, 1e-30f), 1.0f);
      const float tau = -log1p(-fmin(alpha, 1.0f - 1e-7f));
      med = t_w[row] + fmin(fmax(log(2.0f * T) / tau, 0.0f), 1.0f) * dt_w[row];
    }
    depth += w * t_w[row];
    w_w[row] = w;
    hc += w > thr ? 1 : 0;
    T *= e;
  }
  if (fine && mc > 1 && hit_alpha > 0.0f && q >= mc) fine = 0, q = 0;
  trans[r] = T;
  acc[3 * r] = depth;
  median[r] = med;
  mode[r] = fine;
  quiet[r] = q;
  last_k[r] = lk;
  hcount[a] = hc;
  done[a] = eps > 0.0f && T < eps;
}

// The head's rows of the wave: alive ray a's rows with w > thr, at head rows hoffset[a] ..:
// their density rows (the head's input), weight and ray.
__kernel void pipeline_gm_head_gather(const int n_alive, const int stride, const float thr,
                                      __global const int* alive, __global const int* offset,
                                      __global const int* hoffset, __global const float* dens,
                                      __global const float* w_w, __global float* dens_h,
                                      __global float* w_h, __global int* ray_h) {
  const int a = get_global_id(0);
  if (a >= n_alive) return;
  const int r = alive[a];
  int out = hoffset[a];
  for (int row = offset[a]; row < offset[a + 1]; ++row) {
    if (!(w_w[row] > thr)) continue;
    for (int c = 0; c < stride; ++c)
      dens_h[(size_t)out * stride + c] = dens[(size_t)row * stride + c];
    w_h[out] = w_w[row];
    ray_h[out] = r;
    ++out;
  }
}

// The head's outputs (logits a, b per row) into the ray's sums, alive ray a over its head rows
// in order: acc[3 r + 1] += w·sigmoid(a), acc[3 r + 2] += w·sigmoid(b).
__kernel void pipeline_gm_head_accumulate(const int n_alive, __global const int* alive,
                                          __global const int* hoffset,
                                          __global const float* head_h,
                                          __global const float* w_h, __global float* acc) {
  const int a = get_global_id(0);
  if (a >= n_alive) return;
  const int r = alive[a];
  float p = acc[3 * r + 1], q = acc[3 * r + 2];
  for (int row = hoffset[a]; row < hoffset[a + 1]; ++row) {
    p += w_h[row] / (1.0f + exp(-head_h[2 * row]));
    q += w_h[row] / (1.0f + exp(-head_h[2 * row + 1]));
  }
  acc[3 * r + 1] = p;
  acc[3 * r + 2] = q;
}

// The outputs: out[3 r] = the expected depth, or with use_median the median (t_last for a ray
// whose weight never reached 1/2, as render_median_depth gives the last sample's t); the
// probability and intensity sums.
__kernel void pipeline_gm_finish(const int n_rays, const int use_median, const float t_last,
                                 __global const float* acc, __global const float* median,
                                 __global float* out) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  out[3 * r + 0] = use_median ? (median[r] < 0.0f ? t_last : median[r]) : acc[3 * r];
  out[3 * r + 1] = acc[3 * r + 1];
  out[3 * r + 2] = acc[3 * r + 2];
}
