// Multi-resolution hash-grid encoding (method.md §0, instant-ngp): forward, race-free
// level-partitioned parameter backward, an atomic (non-deterministic) parameter backward, the
// pairs of the deterministic parallel backward (field/entry_reduce.cl), and the input-position
// backward d_x that carries gradients into poses.
//
// Defines: LEVELS (L), FEATURES (F, 1..8), HALF_TABLE (0|1), CHUNK. Level table `meta` holds
// per level (res, entry offset, entry count, hashed flag); `scale` the float grid scale. Entry e of level l stores its F
// features at params[param_offset + (meta.offset + e) * F + f]. Encoding layout: enc[n*L*F + l*F + f].
// x is N×3 in [-1, 1]; it is mapped to [0, 1] and then pos = x01 * scale + 0.5 (instant-ngp).
#ifndef LEVELS
#error "LEVELS must be defined"
#endif
#ifndef FEATURES
#error "FEATURES must be defined"
#endif
#ifndef HALF_TABLE
#define HALF_TABLE 0
#endif
#ifndef CHUNK
#define CHUNK 256  // points per work-item of the chunked (CPU) schedule
#endif
#define LF (LEVELS * FEATURES)

#include "common/atomic_add.clh"
#include "field/hashgrid.clh"

// One work-item per (point, level); the level is the slow dimension (level-major scheduling).
// Straight-line scalar body without early exits, so the work-group loop vectorises across
// work-items (tail work-items read point n − 1 and skip the store).
__kernel void field_hashgrid_fwd(const int n, __global const table_t* params, const uint param_offset,
                                 __global const float* x, __global const float* scale,
                                 __global const uint4* meta, __global const float* level_weight,
                                 __global float* enc) {
  const int i = get_global_id(0);
  const int l = get_global_id(1);
  const int ii = min(i, n - 1);
  const float w = level_weight[l];
  const uint4 m = meta[l];
  const float s = scale[l];
  const float px = fma(fma(x[3 * ii + 0], 0.5f, 0.5f), s, 0.5f);
  const float py = fma(fma(x[3 * ii + 1], 0.5f, 0.5f), s, 0.5f);
  const float pz = fma(fma(x[3 * ii + 2], 0.5f, 0.5f), s, 0.5f);
  const float flx = floor(px), fly = floor(py), flz = floor(pz);
  const float3 fr = (float3)(px - flx, py - fly, pz - flz);
  const uint3 g = (uint3)((uint)(int)flx, (uint)(int)fly, (uint)(int)flz);
  __global const table_t* t = params + param_offset + (size_t)m.y * FEATURES;
  featv acc = (featv)(0.0f);
#define FWD_CORNER(cx, cy, cz) \
  acc = fma((featv)(CORNER_W(cx, cy, cz, fr)), LOADT(t + (int)(CORNER_E(cx, cy, cz, g, m) * FEATURES)), acc)
  FWD_CORNER(0, 0, 0); FWD_CORNER(1, 0, 0); FWD_CORNER(0, 1, 0); FWD_CORNER(1, 1, 0);
  FWD_CORNER(0, 0, 1); FWD_CORNER(1, 0, 1); FWD_CORNER(0, 1, 1); FWD_CORNER(1, 1, 1);
#undef FWD_CORNER
  if (i < n) STOREF(w * acc, enc + (size_t)i * LF + l * FEATURES);
}

// Forward, chunked (the CPU schedule): one work-item per (chunk of CHUNK points, level) looping
// over its points; same arithmetic as field_hashgrid_fwd. On PoCL a plain serial loop per
// work-item beats the vectorised work-group loop of the per-point kernel for these gathers.
__kernel void field_hashgrid_fwd_chunk(const int n, __global const table_t* params,
                                       const uint param_offset, __global const float* x,
                                       __global const float* scale, __global const uint4* meta,
                                       __global const float* level_weight, __global float* enc) {
  const int c = get_global_id(0);
  const int l = get_global_id(1);
  const float w = level_weight[l];
  const uint4 m = meta[l];
  const float s = scale[l];
  __global const table_t* t = params + param_offset + (size_t)m.y * FEATURES;
  const int end = min(n, (c + 1) * CHUNK);
  for (int i = c * CHUNK; i < end; ++i) {
    uint3 g;
    const float3 fr = hg_locate(x, i, s, &g);
    featv acc = (featv)(0.0f);
#define FWD_CORNER(cx, cy, cz) \
  acc = fma((featv)(CORNER_W(cx, cy, cz, fr)), LOADT(t + (int)(CORNER_E(cx, cy, cz, g, m) * FEATURES)), acc)
    FWD_CORNER(0, 0, 0); FWD_CORNER(1, 0, 0); FWD_CORNER(0, 1, 0); FWD_CORNER(1, 1, 0);
    FWD_CORNER(0, 0, 1); FWD_CORNER(1, 0, 1); FWD_CORNER(0, 1, 1); FWD_CORNER(1, 1, 1);
#undef FWD_CORNER
    STOREF(w * acc, enc + (size_t)i * LF + l * FEATURES);
  }
}

// Deterministic parameter gradient: one work-item per level owns its slice of the gradient
// (overwrites it with zeros, then accumulates over the points in index order). No atomics.
__kernel void field_hashgrid_bwd(const int n, __global const float* x, __global const float* scale,
                                 __global const uint4* meta, __global const float* level_weight,
                                 __global const float* d_enc, __global float* grad,
                                 const uint grad_offset) {
  const int l = get_global_id(0);
  if (l >= LEVELS) return;
  const uint4 m = meta[l];
  __global float* t = grad + grad_offset + (size_t)m.y * FEATURES;
  for (uint e = 0; e < m.z * FEATURES; ++e) t[e] = 0.0f;
  const float w = level_weight[l];
  if (w == 0.0f) return;
  const float s = scale[l];
  for (int i = 0; i < n; ++i) {
    const featv de = w * LOADF(d_enc + (size_t)i * LF + l * FEATURES);
    uint3 g;
    const float3 fr = hg_locate(x, i, s, &g);
#define BWD_CORNER(cx, cy, cz)                                              \
  {                                                                         \
    __global float* p = t + (size_t)CORNER_E(cx, cy, cz, g, m) * FEATURES;  \
    STOREF(fma((featv)(CORNER_W(cx, cy, cz, fr)), de, LOADF(p)), p);        \
  }
    BWD_CORNER(0, 0, 0) BWD_CORNER(1, 0, 0) BWD_CORNER(0, 1, 0) BWD_CORNER(1, 1, 0)
    BWD_CORNER(0, 0, 1) BWD_CORNER(1, 0, 1) BWD_CORNER(0, 1, 1) BWD_CORNER(1, 1, 1)
#undef BWD_CORNER
  }
}

// Non-deterministic parameter gradient: one work-item per (point, level), atomic adds into a
// gradient slice the caller has zeroed (common/atomic_add.clh). Summation order varies
// between runs.
__kernel void field_hashgrid_bwd_atomic(const int n, __global const float* x,
                                        __global const float* scale, __global const uint4* meta,
                                        __global const float* level_weight,
                                        __global const float* d_enc, __global float* grad,
                                        const uint grad_offset) {
  const int i = get_global_id(0);
  const int l = get_global_id(1);
  if (i >= n) return;
  const float w = level_weight[l];
  if (w == 0.0f) return;
  const uint4 m = meta[l];
  __global float* t = grad + grad_offset + (size_t)m.y * FEATURES;
  uint3 g;
  const float3 fr = hg_locate(x, i, scale[l], &g);
  for (int c = 0; c < 8; ++c) {
    const uint cx = c & 1, cy = (c >> 1) & 1, cz = c >> 2;
    const float wc = CORNER_W(cx, cy, cz, fr) * w;
    const uint e = CORNER_E(cx, cy, cz, g, m);
    for (int f = 0; f < FEATURES; ++f)
      atomic_add_float(t + (size_t)e * FEATURES + f, wc * d_enc[(size_t)i * LF + l * FEATURES + f]);
  }
}

// The pairs of the deterministic parallel backward (field/entry_reduce.cl, unit = level, 8
// pairs per point, one vector per point): one work-item per (point, level) writes, for corner
// c of point i, pair j = 8i + c: key = the entry (from the module slice's start), coef = the
// corner's trilinear weight, and vec[l·n + i] = w_l · d_enc[i, l] (zero for a level of weight
// 0, whose serial gradient is zero). The same expressions as field_hashgrid_bwd, so the sums
// entry_reduce forms in pair order equal it bit for bit.
__kernel void field_hashgrid_bwd_pairs(const int n, __global const float* x,
                                       __global const float* scale, __global const uint4* meta,
                                       __global const float* level_weight,
                                       __global const float* d_enc, __global uint* keys,
                                       __global uint* vals, __global float* coef,
                                       __global float* vec) {
  const int i = get_global_id(0);
  const int l = get_global_id(1);
  if (i >= n) return;
  const float w = level_weight[l];
  const uint4 m = meta[l];
  const featv de = w == 0.0f ? (featv)(0.0f) : w * LOADF(d_enc + (size_t)i * LF + l * FEATURES);
  STOREF(de, vec + ((size_t)l * n + i) * FEATURES);
  uint3 g;
  const float3 fr = hg_locate(x, i, scale[l], &g);
  const size_t base = ((size_t)l * n + i) * 8;
#define PAIR_CORNER(c, cx, cy, cz)                            \
  keys[base + c] = m.y + CORNER_E(cx, cy, cz, g, m);          \
  vals[base + c] = (uint)i * 8u + c;                          \
  coef[base + c] = CORNER_W(cx, cy, cz, fr);
  PAIR_CORNER(0, 0, 0, 0) PAIR_CORNER(1, 1, 0, 0) PAIR_CORNER(2, 0, 1, 0) PAIR_CORNER(3, 1, 1, 0)
  PAIR_CORNER(4, 0, 0, 1) PAIR_CORNER(5, 1, 0, 1) PAIR_CORNER(6, 0, 1, 1) PAIR_CORNER(7, 1, 1, 1)
#undef PAIR_CORNER
}

// Input-position gradient, level-major like the forward: one work-item per (point, level)
// writes its level's contribution w_l · scale_l · 0.5 · Σ_f d_enc[i,l,f] · ∂interp/∂pos (from
// the derivatives of the trilinear weights, smooth inside each cell) to part[l][i] (3 floats);
// field_hashgrid_dx_reduce then sums the levels in order.
__kernel void field_hashgrid_bwd_dx(const int n, __global const table_t* params,
                                    const uint param_offset, __global const float* x,
                                    __global const float* scale, __global const uint4* meta,
                                    __global const float* level_weight,
                                    __global const float* d_enc, __global float* part) {
  const int i = get_global_id(0);
  const int l = get_global_id(1);
  if (i >= n) return;
  const float w = level_weight[l];
  float3 dp = (float3)(0.0f);
  if (w != 0.0f) {
    const uint4 m = meta[l];
    const float s = scale[l];
    uint3 g;
    const float3 fr = hg_locate(x, i, s, &g);
    const float3 om = (float3)(1.0f) - fr;
    __global const table_t* t = params + param_offset + (size_t)m.y * FEATURES;
    const featv de = LOADF(d_enc + (size_t)i * LF + l * FEATURES);
    DX_CORNER(0, 0, 0) DX_CORNER(1, 0, 0) DX_CORNER(0, 1, 0) DX_CORNER(1, 1, 0)
    DX_CORNER(0, 0, 1) DX_CORNER(1, 0, 1) DX_CORNER(0, 1, 1) DX_CORNER(1, 1, 1)
    dp *= w * s * 0.5f;
  }
  vstore3(dp, (size_t)l * n + i, part);
}

// d_x contributions, chunked (the CPU schedule): as field_hashgrid_bwd_dx, looping over CHUNK
// points per work-item.
__kernel void field_hashgrid_bwd_dx_chunk(const int n, __global const table_t* params,
                                          const uint param_offset, __global const float* x,
                                          __global const float* scale, __global const uint4* meta,
                                          __global const float* level_weight,
                                          __global const float* d_enc, __global float* part) {
  const int c = get_global_id(0);
  const int l = get_global_id(1);
  const float w = level_weight[l];
  const uint4 m = meta[l];
  const float s = scale[l];
  __global const table_t* t = params + param_offset + (size_t)m.y * FEATURES;
  const int end = min(n, (c + 1) * CHUNK);
  for (int i = c * CHUNK; i < end; ++i) {
    float3 dp = (float3)(0.0f);
    if (w != 0.0f) {
      uint3 g;
      const float3 fr = hg_locate(x, i, s, &g);
      const float3 om = (float3)(1.0f) - fr;
      const featv de = LOADF(d_enc + (size_t)i * LF + l * FEATURES);
      DX_CORNER(0, 0, 0) DX_CORNER(1, 0, 0) DX_CORNER(0, 1, 0) DX_CORNER(1, 1, 0)
      DX_CORNER(0, 0, 1) DX_CORNER(1, 0, 1) DX_CORNER(0, 1, 1) DX_CORNER(1, 1, 1)
      dp *= w * s * 0.5f;
    }
    vstore3(dp, (size_t)l * n + i, part);
  }
}

// d_x[i] = Σ_l part[l][i], levels in order (deterministic).
__kernel void field_hashgrid_dx_reduce(const int n, __global const float* part,
                                       __global float* d_x) {
  const int i = get_global_id(0);
  if (i >= n) return;
  float3 acc = vload3(i, part);
  for (int l = 1; l < LEVELS; ++l) acc += vload3((size_t)l * n + i, part);
  vstore3(acc, i, d_x);
}

// Zeroes count floats of buf from offset (the atomic path accumulates into a zeroed slice).
__kernel void field_hashgrid_zero(__global float* buf, const uint offset, const uint count) {
  const uint i = get_global_id(0);
  if (i < count) buf[offset + i] = 0.0f;
}

// fp16 copy of the table for HALF_TABLE forward/d_x: half_table[i] = params[offset + i] (RTE;
// inf/NaN are not expected in a trained table and are not special-cased by the decoder).
__kernel void field_hashgrid_to_half(__global const float* params, const uint offset,
                                     const uint count, __global half* half_table) {
  const uint i = get_global_id(0);
  if (i < count) vstore_half_rte(params[offset + i], i, half_table);
}
