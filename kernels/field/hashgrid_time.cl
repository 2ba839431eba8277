// Time-sliced 2D hash grids (method.md §2, LiDAR4D's dynamic hash encoding): three planes xy,
// xz, yz, each a stack of SLICES 2D multi-resolution hash grids (one per time slice); a time t
// blends its two neighbouring slices linearly, and the three planes' blended features are
// multiplied (Hadamard) per level. Forward, and a race-free level-partitioned parameter
// backward that also gives the input-position gradient d_x; its parallel forms (per point and
// level: atomic adds, or the pairs of the deterministic backward of field/entry_reduce.cl).
//
// Defines: LEVELS (L), FEATURES (F, 1..8), SLICES (T ≥ 1), CHUNK (points per work-item of the
// forward; 1 = one work-item per point); the backward runs L work-items.
// meta[p·L + l] = (res, entry offset within one slice, entries, hashed) of level l of plane p;
// pmeta[p] = (first entry of plane p in the module slice, entries per time slice); entry e of
// slice s, level l, plane p stores F floats at
// params[param_offset + (pmeta.x + s·pmeta.y + meta.y + e)·F + f]. A level indexes (gx, gy)
// densely (gx + gy·res, clamped) when res² fits the table, else by the spatial hash
// gx ⊕ gy·2654435761 (instant-ngp), as kernels/field/hashgrid.clh does in 3D.
// Position: pos = ((x + 1)/2)·scale_l + 0.5 per axis (x ∈ [−1, 1]); time:
// u = clamp(t, 0, 1)·(T − 1), slices s0 = floor(u), s1 = min(s0 + 1, T − 1), weights
// (1 − (u − s0), u − s0).
// Encoding columns: enc[i·stride + col + l·F + f].
// One time for every point (LiDAR4D's batches are one frame each): field_hashgrid_time_blend
// writes the two slices' blend w0·slice s0 + w1·slice s1 of each plane as a one-slice table,
// which the SLICES = 1 build of the forward and backward reads (4 corner reads per plane
// instead of 8, and no t), and field_hashgrid_time_spread adds that one-slice gradient back to
// the two slices with the same weights.
#ifndef LEVELS
#error "LEVELS must be defined"
#endif
#ifndef FEATURES
#error "FEATURES must be defined"
#endif
#ifndef SLICES
#error "SLICES must be defined"
#endif
#ifndef CHUNK
#define CHUNK 64
#endif
#define HALF_TABLE 0
#include "common/atomic_add.clh"
#include "field/hashgrid.clh"

// Contributions per point of one level in the parallel backwards: 3 planes × 4 corners × the
// slices written (2, or 1 with one slice); pair j = (p·4 + c)·TH_SLOTS + slot.
#define TH_SLOTS (SLICES > 1 ? 2 : 1)
#define TH_PAIRS (12 * TH_SLOTS)

// The two spatial axes of plane p: xy, xz, yz.
inline int th_axis_a(int p) { return p == 2 ? 1 : 0; }
inline int th_axis_b(int p) { return p == 0 ? 1 : 2; }

// The neighbouring time slices of time tv and the weight of the later one.
inline int th_slices_at(float tv, int* s1, float* w1) {
  const float u = clamp(tv, 0.0f, 1.0f) * (float)(SLICES - 1);
  const int s0 = min((int)floor(u), SLICES - 1);
  *s1 = min(s0 + 1, SLICES - 1);
  *w1 = u - (float)s0;
  return s0;
}

// ... of point i (with one slice t is not read: slice 0, weight 0).
inline int th_slices(__global const float* t, int i, int* s1, float* w1) {
#if SLICES == 1
  *s1 = 0;
  *w1 = 0.0f;
  return 0;
#else
  return th_slices_at(t[i], s1, w1);
#endif
}

// Time blend of a corner entry of the two slices (one slice: the entry itself).
#if SLICES == 1
#define TH_BLEND(t0, t1, w0, w1, e) LOADF((t0) + (e))
#else
#define TH_BLEND(t0, t1, w0, w1, e) ((w0) * LOADF((t0) + (e)) + (w1) * LOADF((t1) + (e)))
#endif

// Grid cell and fraction of point i on plane p at level scale sc.
inline float2 th_locate(__global const float* x, int i, int p, float sc, uint2* g) {
  const float pa = fma(fma(x[3 * i + th_axis_a(p)], 0.5f, 0.5f), sc, 0.5f);
  const float pb = fma(fma(x[3 * i + th_axis_b(p)], 0.5f, 0.5f), sc, 0.5f);
  const float2 fl = (float2)(floor(pa), floor(pb));
  *g = (uint2)((uint)(int)fl.x, (uint)(int)fl.y);
  return (float2)(pa, pb) - fl;
}

// Bilinear sample of the time-blended corners w0·t0[e] + w1·t1[e] of two slices' level tables
// (the corner indices computed once); with da non-null also ∂/∂pos_a and ∂/∂pos_b.
inline featv th_bilerp(__global const float* t0, __global const float* t1, float w0, float w1,
                       uint4 m, uint2 g, float2 fr, featv* da, featv* db) {
  const size_t e00 = (size_t)hg_index(g.x, g.y, 0u, m) * FEATURES;
  const size_t e10 = (size_t)hg_index(g.x + 1u, g.y, 0u, m) * FEATURES;
  const size_t e01 = (size_t)hg_index(g.x, g.y + 1u, 0u, m) * FEATURES;
  const size_t e11 = (size_t)hg_index(g.x + 1u, g.y + 1u, 0u, m) * FEATURES;
  const featv v00 = TH_BLEND(t0, t1, w0, w1, e00);
  const featv v10 = TH_BLEND(t0, t1, w0, w1, e10);
  const featv v01 = TH_BLEND(t0, t1, w0, w1, e01);
  const featv v11 = TH_BLEND(t0, t1, w0, w1, e11);
  const featv lo = fma((featv)(fr.x), v10 - v00, v00), hi = fma((featv)(fr.x), v11 - v01, v01);
  if (da) {
    *da = fma((featv)(fr.y), (v11 - v01) - (v10 - v00), v10 - v00);
    *db = hi - lo;
  }
  return fma((featv)(fr.y), hi - lo, lo);
}

// Time-blended feature of plane p, level l at point i (and its position derivatives, scaled
// to ∂/∂x, when da is non-null).
inline featv th_plane(__global const float* tbl, __global const uint4* meta,
                      __global const uint2* pmeta, float sc, int p, int l,
                      __global const float* x, __global const float* t, int i, featv* da,
                      featv* db) {
  const uint4 m = meta[p * LEVELS + l];
  const uint2 pm = pmeta[p];
  int s1;
  float w1;
  const int s0 = th_slices(t, i, &s1, &w1);
  uint2 g;
  const float2 fr = th_locate(x, i, p, sc, &g);
  __global const float* t0 = tbl + (size_t)(pm.x + (uint)s0 * pm.y + m.y) * FEATURES;
  __global const float* t1 = tbl + (size_t)(pm.x + (uint)s1 * pm.y + m.y) * FEATURES;
  const featv v = th_bilerp(t0, t1, 1.0f - w1, w1, m, g, fr, da, db);
  if (da) {
    *da *= 0.5f * sc;
    *db *= 0.5f * sc;
  }
  return v;
}

// One work-item per (chunk of CHUNK points, level).
__kernel void field_hashgrid_time_fwd(const int n, __global const float* params,
                                      const uint param_offset, __global const float* x,
                                      __global const float* t, __global const float* scale,
                                      __global const uint4* meta, __global const uint2* pmeta,
                                      __global float* enc, const int stride, const int col) {
  const int c = get_global_id(0), l = get_global_id(1);
  const float sc = scale[l];
  __global const float* tbl = params + param_offset;
  const int end = min(n, (c + 1) * CHUNK);
  for (int i = c * CHUNK; i < end; ++i) {
    featv v = th_plane(tbl, meta, pmeta, sc, 0, l, x, t, i, 0, 0);
    v *= th_plane(tbl, meta, pmeta, sc, 1, l, x, t, i, 0, 0);
    v *= th_plane(tbl, meta, pmeta, sc, 2, l, x, t, i, 0, 0);
    STOREF(v, enc + (size_t)i * stride + col + l * FEATURES);
  }
}

// Deterministic parameter gradient, and with with_dx the input-position gradient from the same
// corner reads: one work-item per level l owns level l of every time slice of the three planes:
// zeroes it (unless accumulate), then, over the points in index order, samples the three
// planes once (corner entries and weights kept) and adds to each d_enc ⊙ (the product of the
// other two) · time weight · bilinear weight; with_dx writes the level's
// Σ_f d_enc · ∂(v0 v1 v2)/∂x to part[l·n + i] (3 floats), which
// field_hashgrid_time_dx_reduce sums in order. No atomics.
__kernel void field_hashgrid_time_bwd(const int n, __global const float* params,
                                      const uint param_offset, __global const float* x,
                                      __global const float* t, __global const float* scale,
                                      __global const uint4* meta, __global const uint2* pmeta,
                                      __global const float* d_enc, const int stride,
                                      const int col, __global float* grad,
                                      const uint grad_offset, const int accumulate,
                                      const int with_dx, __global float* part) {
  const int l = get_global_id(0);
  const float sc = scale[l];
  __global const float* tbl = params + param_offset;
  __global float* gr = grad + grad_offset;
  if (!accumulate)
    for (int p = 0; p < 3; ++p) {
      const uint4 m = meta[p * LEVELS + l];
      const uint2 pm = pmeta[p];
      for (int s = 0; s < SLICES; ++s) {
        __global float* q = gr + (size_t)(pm.x + (uint)s * pm.y + m.y) * FEATURES;
        for (uint e = 0; e < m.z * FEATURES; ++e) q[e] = 0.0f;
      }
    }
  for (int i = 0; i < n; ++i) {
    const featv de = LOADF(d_enc + (size_t)i * stride + col + l * FEATURES);
    int s1;
    float w1;
    const int s0 = th_slices(t, i, &s1, &w1);
    const float w0 = 1.0f - w1;
    uint e0[3][4], e1[3][4];
    float w[3][4];
    featv v[3], da[3], db[3];
    for (int p = 0; p < 3; ++p) {
      const uint4 m = meta[p * LEVELS + l];
      const uint2 pm = pmeta[p];
      uint2 g;
      const float2 fr = th_locate(x, i, p, sc, &g);
      const uint o0 = pm.x + (uint)s0 * pm.y + m.y, o1 = pm.x + (uint)s1 * pm.y + m.y;
      featv cv[4];  // time-blended corners
      for (int c = 0; c < 4; ++c) {
        const uint cx = c & 1, cy = c >> 1;
        const uint e = hg_index(g.x + cx, g.y + cy, 0u, m);
        w[p][c] = (cx ? fr.x : 1.0f - fr.x) * (cy ? fr.y : 1.0f - fr.y);
        e0[p][c] = o0 + e;
        e1[p][c] = o1 + e;
        cv[c] = TH_BLEND(tbl + (size_t)e0[p][c] * FEATURES, tbl + (size_t)e1[p][c] * FEATURES,
                         w0, w1, 0);
      }
      v[p] = w[p][0] * cv[0] + w[p][1] * cv[1] + w[p][2] * cv[2] + w[p][3] * cv[3];
      da[p] = (0.5f * sc) * fma((featv)(fr.y), (cv[3] - cv[2]) - (cv[1] - cv[0]), cv[1] - cv[0]);
      db[p] = (0.5f * sc) * fma((featv)(fr.x), (cv[3] - cv[1]) - (cv[2] - cv[0]), cv[2] - cv[0]);
    }
    const featv gq[3] = {de * v[1] * v[2], de * v[0] * v[2], de * v[0] * v[1]};
    for (int p = 0; p < 3; ++p)
      for (int c = 0; c < 4; ++c) {
        __global float* q0 = gr + (size_t)e0[p][c] * FEATURES;
        STOREF(fma((featv)(w0 * w[p][c]), gq[p], LOADF(q0)), q0);
#if SLICES > 1
        __global float* q1 = gr + (size_t)e1[p][c] * FEATURES;
        STOREF(fma((featv)(w1 * w[p][c]), gq[p], LOADF(q1)), q1);
#endif
      }
    if (with_dx)  // xy, xz, yz: x from xy and xz, y from xy and yz, z from xz and yz
      vstore3((float3)(hg_sum(gq[0] * da[0] + gq[1] * da[1]), hg_sum(gq[0] * db[0] + gq[2] * da[2]),
                       hg_sum(gq[1] * db[1] + gq[2] * db[2])),
              (size_t)l * n + i, part);
  }
}

// The parallel backwards, one work-item per (point i, level l), with field_hashgrid_time_bwd's
// arithmetic for one point (the same expressions, so the pair sums equal it bit for bit) and
// its d_x part. atomic = 0: the pairs of the deterministic parallel backward
// (field/entry_reduce.cl; unit = level, TH_PAIRS pairs per point, one vector per plane):
// keys[base + j] = the entry, coef = time weight · bilinear weight, vec = the plane's
// d_enc ⊙ (product of the other two planes). atomic = 1: adds the same terms into grad with
// compare-and-swap float adds (common/atomic_add.clh; order varies), after the caller zeroed
// the gradient unless accumulating.
__kernel void field_hashgrid_time_bwd_points(
    const int n, __global const float* params, const uint param_offset, __global const float* x,
    __global const float* t, __global const float* scale, __global const uint4* meta,
    __global const uint2* pmeta, __global const float* d_enc, const int stride, const int col,
    const int atomic, __global uint* keys, __global uint* vals, __global float* coef,
    __global float* vec, __global float* grad, const uint grad_offset, const int with_dx,
    __global float* part) {
  const int i = get_global_id(0), l = get_global_id(1);
  if (i >= n) return;
  const float sc = scale[l];
  __global const float* tbl = params + param_offset;
  const featv de = LOADF(d_enc + (size_t)i * stride + col + l * FEATURES);
  int s1;
  float w1;
  const int s0 = th_slices(t, i, &s1, &w1);
  const float w0 = 1.0f - w1;
  uint e0[3][4], e1[3][4];
  float w[3][4];
  featv v[3], da[3], db[3];
  for (int p = 0; p < 3; ++p) {
    const uint4 m = meta[p * LEVELS + l];
    const uint2 pm = pmeta[p];
    uint2 g;
    const float2 fr = th_locate(x, i, p, sc, &g);
    const uint o0 = pm.x + (uint)s0 * pm.y + m.y, o1 = pm.x + (uint)s1 * pm.y + m.y;
    featv cv[4];  // time-blended corners
    for (int c = 0; c < 4; ++c) {
      const uint cx = c & 1, cy = c >> 1;
      const uint e = hg_index(g.x + cx, g.y + cy, 0u, m);
      w[p][c] = (cx ? fr.x : 1.0f - fr.x) * (cy ? fr.y : 1.0f - fr.y);
      e0[p][c] = o0 + e;
      e1[p][c] = o1 + e;
      cv[c] = TH_BLEND(tbl + (size_t)e0[p][c] * FEATURES, tbl + (size_t)e1[p][c] * FEATURES,
                       w0, w1, 0);
    }
    v[p] = w[p][0] * cv[0] + w[p][1] * cv[1] + w[p][2] * cv[2] + w[p][3] * cv[3];
    da[p] = (0.5f * sc) * fma((featv)(fr.y), (cv[3] - cv[2]) - (cv[1] - cv[0]), cv[1] - cv[0]);
    db[p] = (0.5f * sc) * fma((featv)(fr.x), (cv[3] - cv[1]) - (cv[2] - cv[0]), cv[2] - cv[0]);
  }
  const featv gq[3] = {de * v[1] * v[2], de * v[0] * v[2], de * v[0] * v[1]};
  if (atomic) {
    __global float* gr = grad + grad_offset;
    for (int p = 0; p < 3; ++p) {
      float gf[FEATURES];
      STOREF(gq[p], gf);
      for (int c = 0; c < 4; ++c)
        for (int f = 0; f < FEATURES; ++f) {
          atomic_add_float(gr + (size_t)e0[p][c] * FEATURES + f, w0 * w[p][c] * gf[f]);
#if SLICES > 1
          atomic_add_float(gr + (size_t)e1[p][c] * FEATURES + f, w1 * w[p][c] * gf[f]);
#endif
        }
    }
  } else {
    const size_t base = ((size_t)l * n + i) * TH_PAIRS;
    for (int p = 0; p < 3; ++p) {
      STOREF(gq[p], vec + (((size_t)l * n + i) * 3 + p) * FEATURES);
      for (int c = 0; c < 4; ++c) {
        const int j = (p * 4 + c) * TH_SLOTS;
        keys[base + j] = e0[p][c];
        vals[base + j] = (uint)i * TH_PAIRS + j;
        coef[base + j] = w0 * w[p][c];
#if SLICES > 1
        keys[base + j + 1] = e1[p][c];
        vals[base + j + 1] = (uint)i * TH_PAIRS + j + 1;
        coef[base + j + 1] = w1 * w[p][c];
#endif
      }
    }
  }
  if (with_dx)  // xy, xz, yz: x from xy and xz, y from xy and yz, z from xz and yz
    vstore3((float3)(hg_sum(gq[0] * da[0] + gq[1] * da[1]), hg_sum(gq[0] * db[0] + gq[2] * da[2]),
                     hg_sum(gq[1] * db[1] + gq[2] * db[2])),
            (size_t)l * n + i, part);
}

// d_x[i] = Σ_l part[l][i], levels in order (deterministic).
__kernel void field_hashgrid_time_dx_reduce(const int n, __global const float* part,
                                            __global float* d_x) {
  const int i = get_global_id(0);
  if (i >= n) return;
  float3 acc = vload3(i, part);
  for (int l = 1; l < LEVELS; ++l) acc += vload3((size_t)l * n + i, part);
  vstore3(acc, i, d_x);
}

// Entry gid of the one-slice table (plane p from entry bmeta[p]): the float offsets of the same
// entry in slices s0 and s1 of the module slice, and their weights at time tv.
inline void th_entry_slices(int gid, float tv, __global const uint2* pmeta,
                            __global const uint* bmeta, size_t* o0, size_t* o1, float* w0,
                            float* w1) {
  const int p = gid >= (int)bmeta[2] ? 2 : (gid >= (int)bmeta[1] ? 1 : 0);
  const uint e = (uint)gid - bmeta[p];
  int s1;
  const int s0 = th_slices_at(tv, &s1, w1);
  *w0 = 1.0f - *w1;
  const uint2 pm = pmeta[p];
  *o0 = (size_t)(pm.x + (uint)s0 * pm.y + e) * FEATURES;
  *o1 = (size_t)(pm.x + (uint)s1 * pm.y + e) * FEATURES;
}

// One time tv for every point: out (planes' one-slice tables one after another, pmeta[p].y
// entries each, plane p from entry bmeta[p]) = w0 · slice s0 + w1 · slice s1 of each plane.
// One work-item per entry of the three planes (gid < total).
__kernel void field_hashgrid_time_blend(const int total, const float tv,
                                        __global const float* params, const uint param_offset,
                                        __global const uint2* pmeta, __global const uint* bmeta,
                                        __global float* out) {
  const int gid = get_global_id(0);
  if (gid >= total) return;
  size_t o0, o1;
  float w0, w1;
  th_entry_slices(gid, tv, pmeta, bmeta, &o0, &o1, &w0, &w1);
  __global const float* tbl = params + param_offset;
  STOREF(TH_BLEND(tbl + o0, tbl + o1, w0, w1, 0), out + (size_t)gid * FEATURES);
}

// The gradient of the blend: grad slice s0 += w0 · g_blend, slice s1 += w1 · g_blend (the
// same entry; one work-item per entry of the three planes, so s0 = s1 at t = 1 is no race).
// Without accumulate the caller has zeroed the module's gradient first.
__kernel void field_hashgrid_time_spread(const int total, const float tv,
                                         __global const uint2* pmeta, __global const uint* bmeta,
                                         __global const float* g_blend, __global float* grad,
                                         const uint grad_offset) {
  const int gid = get_global_id(0);
  if (gid >= total) return;
  size_t o0, o1;
  float w0, w1;
  th_entry_slices(gid, tv, pmeta, bmeta, &o0, &o1, &w0, &w1);
  const featv g = LOADF(g_blend + (size_t)gid * FEATURES);
  __global float* q0 = grad + grad_offset + o0;
  STOREF(fma((featv)(w0), g, LOADF(q0)), q0);
  __global float* q1 = grad + grad_offset + o1;
  STOREF(fma((featv)(w1), g, LOADF(q1)), q1);
}

// Zero grad[grad_offset, + count) (count floats; one work-item each).
__kernel void field_hashgrid_time_zero(const uint count, __global float* grad,
                                       const uint grad_offset) {
  const uint i = get_global_id(0);
  if (i < count) grad[grad_offset + i] = 0.0f;
}
