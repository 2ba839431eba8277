// K-Planes-style 4D plane encoding (method.md §2, LiDAR4D's planes): forward, and a race-free
// (scale, group)-partitioned parameter backward that also gives the input-position gradient d_x
// (LiDAR4D samples the dynamic planes at x + scene flow, so the flow network learns through d_x).
// The serial backward runs S·groups work-items: enough for a CPU, too few for a GPU (as the hash
// grid's); its parallel forms run per (point, scale-group): atomic adds, or the pairs of the
// deterministic backward of field/entry_reduce.cl.
//
// Defines: SCALES (S), FEATURES (F, 1..8), CHUNK (points per work-item of the forward; 1 = one
// work-item per point, the GPU schedule). Planes per scale, in order: static xy, xz, yz,
// dynamic xt, yt, zt (plane p = 3·group + k). meta[s·6 + p] = (entry offset in the module
// slice, width W = grid points of the plane's first axis, height H = of its second axis, 0);
// entry (i, j) of a plane is i + j·W and stores F floats (entry-major).
// Coordinates (align_corners, border padding): a spatial axis of R points maps x ∈ [−1, 1] to
// pos = (clamp(x) + 1)/2 · (R − 1); time maps t ∈ [0, 1] to clamp(t) · (T − 1). Bilinear over
// the cell min(floor(pos), R − 2). Per scale and group the feature is the Hadamard product of
// the group's three planes. Encoding columns: enc[i·stride + col + (gi·S + s)·F + f] for the
// gi-th group computed (groups group_first .. group_first + n_groups − 1; 0 static, 1 dynamic).
#ifndef SCALES
#error "SCALES must be defined"
#endif
#ifndef FEATURES
#error "FEATURES must be defined"
#endif
#ifndef CHUNK
#define CHUNK 64
#endif
#define HALF_TABLE 0
#include "common/atomic_add.clh"
#include "field/hashgrid.clh"

// The two axes of plane p (0, 1, 2 = x, y, z; 3 = t).
inline int kp_axis_a(int p) { return p == 2 ? 1 : (p == 4 ? 1 : (p == 5 ? 2 : 0)); }
inline int kp_axis_b(int p) { return p == 0 ? 1 : (p == 1 || p == 2 ? 2 : 3); }

// Grid position of point i along `axis` on a grid of `res` points; *dfac = ∂pos/∂x (0 for
// time, and outside the box where the border padding makes the encoding constant).
inline float kp_pos(__global const float* x, __global const float* t, int i, int axis, uint res,
                    float* dfac) {
  const float span = (float)(res - 1u);
  if (axis == 3) {
    *dfac = 0.0f;
    return clamp(t[i], 0.0f, 1.0f) * span;
  }
  const float v = x[3 * i + axis];
  *dfac = (v > -1.0f && v < 1.0f) ? 0.5f * span : 0.0f;
  return (clamp(v, -1.0f, 1.0f) + 1.0f) * 0.5f * span;
}

// Cell index and fraction of a position on a grid of res ≥ 2 points.
inline uint kp_cell(float pos, uint res, float* fr) {
  const uint c = min((uint)floor(pos), res - 2u);
  *fr = pos - (float)c;
  return c;
}

// Bilinear sample of plane m at (pa, pb); with d_a / d_b non-null also ∂/∂pa and ∂/∂pb.
inline featv kp_sample(__global const float* tbl, uint4 m, float pa, float pb, featv* d_a,
                       featv* d_b) {
  float fa, fb;
  const uint ia = kp_cell(pa, m.y, &fa), ib = kp_cell(pb, m.z, &fb);
  __global const float* e = tbl + (size_t)(m.x + ia + ib * m.y) * FEATURES;
  const featv v00 = LOADF(e), v10 = LOADF(e + FEATURES);
  const featv v01 = LOADF(e + (size_t)m.y * FEATURES);
  const featv v11 = LOADF(e + (size_t)(m.y + 1u) * FEATURES);
  const featv lo = fma((featv)(fa), v10 - v00, v00), hi = fma((featv)(fa), v11 - v01, v01);
  if (d_a) {
    *d_a = fma((featv)(fb), (v11 - v01) - (v10 - v00), v10 - v00);
    *d_b = hi - lo;
  }
  return fma((featv)(fb), hi - lo, lo);
}

// Scatter g · (bilinear weights at (pa, pb)) into the gradient plane m (owned by the caller).
inline void kp_scatter(__global float* tbl, uint4 m, float pa, float pb, featv g) {
  float fa, fb;
  const uint ia = kp_cell(pa, m.y, &fa), ib = kp_cell(pb, m.z, &fb);
  __global float* e = tbl + (size_t)(m.x + ia + ib * m.y) * FEATURES;
  __global float* e01 = e + (size_t)m.y * FEATURES;
  STOREF(fma((featv)((1.0f - fa) * (1.0f - fb)), g, LOADF(e)), e);
  STOREF(fma((featv)(fa * (1.0f - fb)), g, LOADF(e + FEATURES)), e + FEATURES);
  STOREF(fma((featv)((1.0f - fa) * fb), g, LOADF(e01)), e01);
  STOREF(fma((featv)(fa * fb), g, LOADF(e01 + FEATURES)), e01 + FEATURES);
}

// Value of plane p (scale s) at point i, and its position derivatives when asked.
inline featv kp_plane(__global const float* tbl, __global const uint4* meta, int s, int p,
                      __global const float* x, __global const float* t, int i, featv* d_a,
                      featv* d_b, float* fac_a, float* fac_b) {
  const uint4 m = meta[s * 6 + p];
  float ga, gb;
  const float pa = kp_pos(x, t, i, kp_axis_a(p), m.y, &ga);
  const float pb = kp_pos(x, t, i, kp_axis_b(p), m.z, &gb);
  if (fac_a) {
    *fac_a = ga;
    *fac_b = gb;
  }
  return kp_sample(tbl, m, pa, pb, d_a, d_b);
}

// One work-item per (chunk of CHUNK points, scale s + S·gi).
__kernel void field_kplanes_fwd(const int n, __global const float* params, const uint param_offset,
                                __global const float* x, __global const float* t,
                                __global const uint4* meta, const int group_first,
                                __global float* enc, const int stride, const int col) {
  const int c = get_global_id(0);
  const int s = get_global_id(1) % SCALES, gi = get_global_id(1) / SCALES;
  const int p0 = 3 * (group_first + gi);
  __global const float* tbl = params + param_offset;
  const int end = min(n, (c + 1) * CHUNK);
  for (int i = c * CHUNK; i < end; ++i) {
    featv v = kp_plane(tbl, meta, s, p0, x, t, i, 0, 0, 0, 0);
    v *= kp_plane(tbl, meta, s, p0 + 1, x, t, i, 0, 0, 0, 0);
    v *= kp_plane(tbl, meta, s, p0 + 2, x, t, i, 0, 0, 0, 0);
    STOREF(v, enc + (size_t)i * stride + col + (gi * SCALES + s) * FEATURES);
  }
}

// Deterministic parameter gradient, and with with_dx the input-position gradient from the same
// corner reads: one work-item per (scale s, group gi), index s + S·gi, owns the group's three
// planes at that scale: zeroes them (unless accumulate), then, over the points in index order,
// samples the three planes once and adds to each d_enc ⊙ (the product of the other two) times
// its bilinear weights; with_dx writes the unit's Σ_f d_enc · ∂(v0 v1 v2)/∂x to
// part[(gi·S + s)·n + i] (3 floats), which field_kplanes_dx_reduce sums in order. No atomics.
__kernel void field_kplanes_bwd(const int n, __global const float* params, const uint param_offset,
                                __global const float* x, __global const float* t,
                                __global const uint4* meta, const int group_first,
                                __global const float* d_enc, const int stride, const int col,
                                __global float* grad, const uint grad_offset,
                                const int accumulate, const int with_dx,
                                __global float* part) {
  const int s = get_global_id(0) % SCALES, gi = get_global_id(0) / SCALES;
  const int p0 = 3 * (group_first + gi);
  __global const float* tbl = params + param_offset;
  __global float* g = grad + grad_offset;
  if (!accumulate)
    for (int k = 0; k < 3; ++k) {
      const uint4 m = meta[s * 6 + p0 + k];
      for (uint e = 0; e < m.y * m.z * FEATURES; ++e) g[(size_t)m.x * FEATURES + e] = 0.0f;
    }
  for (int i = 0; i < n; ++i) {
    const featv de = LOADF(d_enc + (size_t)i * stride + col + (gi * SCALES + s) * FEATURES);
    featv v[3], da[3], db[3];
    float pa[3], pb[3], fa[3], fb[3];
    for (int k = 0; k < 3; ++k) {
      const uint4 m = meta[s * 6 + p0 + k];
      pa[k] = kp_pos(x, t, i, kp_axis_a(p0 + k), m.y, &fa[k]);
      pb[k] = kp_pos(x, t, i, kp_axis_b(p0 + k), m.z, &fb[k]);
      v[k] = kp_sample(tbl, m, pa[k], pb[k], &da[k], &db[k]);
    }
    const featv g0 = de * v[1] * v[2], g1 = de * v[0] * v[2], g2 = de * v[0] * v[1];
    kp_scatter(g, meta[s * 6 + p0], pa[0], pb[0], g0);
    kp_scatter(g, meta[s * 6 + p0 + 1], pa[1], pb[1], g1);
    kp_scatter(g, meta[s * 6 + p0 + 2], pa[2], pb[2], g2);
    if (with_dx) {
      const float d0 = fa[0] * hg_sum(g0 * da[0]), d1 = fa[1] * hg_sum(g1 * da[1]);
      const float d2 = fa[2] * hg_sum(g2 * da[2]);
      float3 dp;
      if (p0 == 0)  // xy, xz, yz: x from xy and xz, y from xy and yz, z from xz and yz
        dp = (float3)(d0 + d1, fb[0] * hg_sum(g0 * db[0]) + d2,
                      fb[1] * hg_sum(g1 * db[1]) + fb[2] * hg_sum(g2 * db[2]));
      else  // xt, yt, zt: time is not differentiated
        dp = (float3)(d0, d1, d2);
      vstore3(dp, (size_t)(gi * SCALES + s) * n + i, part);
    }
  }
}

// The parallel backwards, one work-item per (point i, scale-group row r = s + S·gi), with
// field_kplanes_bwd's arithmetic for one point (the same expressions, so the pair sums equal it
// bit for bit) and its d_x part. atomic = 0: the pairs of the deterministic parallel backward
// (field/entry_reduce.cl; unit = row, 12 pairs per point: plane k's corners 00, 10, 01, 11 as
// kp_scatter visits them, j = 4k + corner; one vector per plane): keys = the entry, coef = the
// bilinear weight, vec = d_enc ⊙ (product of the other two planes). atomic = 1: adds the same
// terms into grad with compare-and-swap float adds (common/atomic_add.clh; order varies), after
// the caller zeroed the planes unless accumulating.
__kernel void field_kplanes_bwd_points(
    const int n, __global const float* params, const uint param_offset, __global const float* x,
    __global const float* t, __global const uint4* meta, const int group_first,
    __global const float* d_enc, const int stride, const int col, const int atomic,
    __global uint* keys, __global uint* vals, __global float* coef, __global float* vec,
    __global float* grad, const uint grad_offset, const int with_dx, __global float* part) {
  const int i = get_global_id(0), r = get_global_id(1);
  if (i >= n) return;
  const int s = r % SCALES, gi = r / SCALES;
  const int p0 = 3 * (group_first + gi);
  __global const float* tbl = params + param_offset;
  const featv de = LOADF(d_enc + (size_t)i * stride + col + (gi * SCALES + s) * FEATURES);
  featv v[3], da[3], db[3];
  float pa[3], pb[3], fa[3], fb[3];
  for (int k = 0; k < 3; ++k) {
    const uint4 m = meta[s * 6 + p0 + k];
    pa[k] = kp_pos(x, t, i, kp_axis_a(p0 + k), m.y, &fa[k]);
    pb[k] = kp_pos(x, t, i, kp_axis_b(p0 + k), m.z, &fb[k]);
    v[k] = kp_sample(tbl, m, pa[k], pb[k], &da[k], &db[k]);
  }
  const featv g0 = de * v[1] * v[2], g1 = de * v[0] * v[2], g2 = de * v[0] * v[1];
  const featv gk[3] = {g0, g1, g2};
  const size_t row = (size_t)r * n + i;
  for (int k = 0; k < 3; ++k) {
    const uint4 m = meta[s * 6 + p0 + k];
    float cfa, cfb;
    const uint ia = kp_cell(pa[k], m.y, &cfa), ib = kp_cell(pb[k], m.z, &cfb);
    const uint e = m.x + ia + ib * m.y;
    const uint ce[4] = {e, e + 1u, e + m.y, e + m.y + 1u};
    const float cw[4] = {(1.0f - cfa) * (1.0f - cfb), cfa * (1.0f - cfb), (1.0f - cfa) * cfb,
                         cfa * cfb};
    if (atomic) {
      float gf[FEATURES];
      STOREF(gk[k], gf);
      for (int c = 0; c < 4; ++c)
        for (int f = 0; f < FEATURES; ++f)
          atomic_add_float(grad + grad_offset + (size_t)ce[c] * FEATURES + f, cw[c] * gf[f]);
    } else {
      STOREF(gk[k], vec + (row * 3 + k) * FEATURES);
      for (int c = 0; c < 4; ++c) {
        keys[row * 12 + k * 4 + c] = ce[c];
        vals[row * 12 + k * 4 + c] = (uint)i * 12u + k * 4 + c;
        coef[row * 12 + k * 4 + c] = cw[c];
      }
    }
  }
  if (with_dx) {
    const float d0 = fa[0] * hg_sum(g0 * da[0]), d1 = fa[1] * hg_sum(g1 * da[1]);
    const float d2 = fa[2] * hg_sum(g2 * da[2]);
    float3 dp;
    if (p0 == 0)  // xy, xz, yz: x from xy and xz, y from xy and yz, z from xz and yz
      dp = (float3)(d0 + d1, fb[0] * hg_sum(g0 * db[0]) + d2,
                    fb[1] * hg_sum(g1 * db[1]) + fb[2] * hg_sum(g2 * db[2]));
    else  // xt, yt, zt: time is not differentiated
      dp = (float3)(d0, d1, d2);
    vstore3(dp, (size_t)(gi * SCALES + s) * n + i, part);
  }
}

// d_x[i] = Σ_k part[k][i] over the `parts` scale-group parts, in order (deterministic).
__kernel void field_kplanes_dx_reduce(const int n, const int parts, __global const float* part,
                                      __global float* d_x) {
  const int i = get_global_id(0);
  if (i >= n) return;
  float3 acc = vload3(i, part);
  for (int k = 1; k < parts; ++k) acc += vload3((size_t)k * n + i, part);
  vstore3(acc, i, d_x);
}
