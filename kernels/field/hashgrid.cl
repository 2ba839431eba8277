// Multi-resolution hash-grid encoding (method.md §0, instant-ngp): forward, race-free
// level-partitioned parameter backward, an atomic (non-deterministic) parameter backward kept for
// comparison, and the input-position backward d_x that carries gradients into poses.
//
// Defines: LEVELS (L), FEATURES (F, 1..8). Level table `meta` holds per level (res, entry offset,
// entry count, hashed flag); `scale` the float grid scale. Entry e of level l stores its F
// features at params[param_offset + (meta.offset + e) * F + f]. Encoding layout: enc[n*L*F + l*F + f].
// x is N×3 in [-1, 1]; it is mapped to [0, 1] and then pos = x01 * scale + 0.5 (instant-ngp).
#ifndef LEVELS
#error "LEVELS must be defined"
#endif
#ifndef FEATURES
#error "FEATURES must be defined"
#endif
#define LF (LEVELS * FEATURES)

// Index of integer grid point g in level (res, size, hashed).
inline uint hg_index(uint gx, uint gy, uint gz, uint4 m) {
  if (m.w) return (gx ^ (gy * 2654435761u) ^ (gz * 805459861u)) & (m.z - 1u);
  return (gx + gy * m.x + gz * m.x * m.x) % m.z;
}

// Grid position of point i at level scale s: integer cell and fractional part.
inline void hg_locate(__global const float* x, int i, float s, uint* g, float* fr) {
  for (int d = 0; d < 3; ++d) {
    const float x01 = fma(x[3 * i + d], 0.5f, 0.5f);
    const float pos = fma(x01, s, 0.5f);
    const float fl = floor(pos);
    g[d] = (uint)(int)fl;
    fr[d] = pos - fl;
  }
}

// One work-item per (point, level); the level is the slow dimension (level-major scheduling).
__kernel void field_hashgrid_fwd(const int n, __global const float* params, const uint param_offset,
                                 __global const float* x, __global const float* scale,
                                 __global const uint4* meta, __global const float* level_weight,
                                 __global float* enc) {
  const int i = get_global_id(0);
  const int l = get_global_id(1);
  if (i >= n) return;
  const float w = level_weight[l];
  float acc[FEATURES];
  for (int f = 0; f < FEATURES; ++f) acc[f] = 0.0f;
  if (w != 0.0f) {
    const uint4 m = meta[l];
    uint g[3];
    float fr[3];
    hg_locate(x, i, scale[l], g, fr);
    __global const float* table = params + param_offset + (size_t)m.y * FEATURES;
    for (int c = 0; c < 8; ++c) {
      const uint cx = c & 1, cy = (c >> 1) & 1, cz = c >> 2;
      const float wc = (cx ? fr[0] : 1.0f - fr[0]) * (cy ? fr[1] : 1.0f - fr[1]) *
                       (cz ? fr[2] : 1.0f - fr[2]);
      const uint e = hg_index(g[0] + cx, g[1] + cy, g[2] + cz, m);
      for (int f = 0; f < FEATURES; ++f) acc[f] = fma(wc, table[(size_t)e * FEATURES + f], acc[f]);
    }
  }
  for (int f = 0; f < FEATURES; ++f) enc[(size_t)i * LF + l * FEATURES + f] = w * acc[f];
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
  __global float* table = grad + grad_offset + (size_t)m.y * FEATURES;
  for (uint e = 0; e < m.z * FEATURES; ++e) table[e] = 0.0f;
  const float w = level_weight[l];
  if (w == 0.0f) return;
  const float s = scale[l];
  for (int i = 0; i < n; ++i) {
    float de[FEATURES];
    for (int f = 0; f < FEATURES; ++f) de[f] = w * d_enc[(size_t)i * LF + l * FEATURES + f];
    uint g[3];
    float fr[3];
    hg_locate(x, i, s, g, fr);
    for (int c = 0; c < 8; ++c) {
      const uint cx = c & 1, cy = (c >> 1) & 1, cz = c >> 2;
      const float wc = (cx ? fr[0] : 1.0f - fr[0]) * (cy ? fr[1] : 1.0f - fr[1]) *
                       (cz ? fr[2] : 1.0f - fr[2]);
      const uint e = hg_index(g[0] + cx, g[1] + cy, g[2] + cz, m);
      for (int f = 0; f < FEATURES; ++f) table[(size_t)e * FEATURES + f] += wc * de[f];
    }
  }
}

// Float add by compare-and-swap (OpenCL 1.2 has no float atomics).
inline void hg_atomic_add(volatile __global float* p, float v) {
  union { uint u; float f; } old, upd;
  do {
    old.f = *p;
    upd.f = old.f + v;
  } while (atomic_cmpxchg((volatile __global uint*)p, old.u, upd.u) != old.u);
}

// Non-deterministic parameter gradient: one work-item per (point, level), atomic adds into a
// gradient slice the caller has zeroed. Summation order varies between runs.
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
  __global float* table = grad + grad_offset + (size_t)m.y * FEATURES;
  uint g[3];
  float fr[3];
  hg_locate(x, i, scale[l], g, fr);
  for (int c = 0; c < 8; ++c) {
    const uint cx = c & 1, cy = (c >> 1) & 1, cz = c >> 2;
    const float wc = (cx ? fr[0] : 1.0f - fr[0]) * (cy ? fr[1] : 1.0f - fr[1]) *
                     (cz ? fr[2] : 1.0f - fr[2]);
    const uint e = hg_index(g[0] + cx, g[1] + cy, g[2] + cz, m);
    for (int f = 0; f < FEATURES; ++f)
      hg_atomic_add(table + (size_t)e * FEATURES + f,
                    wc * w * d_enc[(size_t)i * LF + l * FEATURES + f]);
  }
}

// Input-position gradient: d_x[i] = Σ_l Σ_f d_enc[i,l,f] · w_l · ∂interp/∂pos · scale_l · 0.5,
// from the derivatives of the trilinear weights (piecewise smooth inside each cell).
__kernel void field_hashgrid_bwd_dx(const int n, __global const float* params,
                                    const uint param_offset, __global const float* x,
                                    __global const float* scale, __global const uint4* meta,
                                    __global const float* level_weight,
                                    __global const float* d_enc, __global float* d_x) {
  const int i = get_global_id(0);
  if (i >= n) return;
  float dx0 = 0.0f, dx1 = 0.0f, dx2 = 0.0f;
  for (int l = 0; l < LEVELS; ++l) {
    const float w = level_weight[l];
    if (w == 0.0f) continue;
    const uint4 m = meta[l];
    const float s = scale[l];
    uint g[3];
    float fr[3];
    hg_locate(x, i, s, g, fr);
    __global const float* table = params + param_offset + (size_t)m.y * FEATURES;
    float dp0 = 0.0f, dp1 = 0.0f, dp2 = 0.0f;
    for (int c = 0; c < 8; ++c) {
      const uint cx = c & 1, cy = (c >> 1) & 1, cz = c >> 2;
      const float wx = cx ? fr[0] : 1.0f - fr[0], sx = cx ? 1.0f : -1.0f;
      const float wy = cy ? fr[1] : 1.0f - fr[1], sy = cy ? 1.0f : -1.0f;
      const float wz = cz ? fr[2] : 1.0f - fr[2], sz = cz ? 1.0f : -1.0f;
      const uint e = hg_index(g[0] + cx, g[1] + cy, g[2] + cz, m);
      float v = 0.0f;  // Σ_f d_enc · feature of this corner
      for (int f = 0; f < FEATURES; ++f)
        v = fma(d_enc[(size_t)i * LF + l * FEATURES + f], table[(size_t)e * FEATURES + f], v);
      dp0 = fma(sx * wy * wz, v, dp0);
      dp1 = fma(wx * sy * wz, v, dp1);
      dp2 = fma(wx * wy * sz, v, dp2);
    }
    const float k = w * s * 0.5f;
    dx0 = fma(k, dp0, dx0);
    dx1 = fma(k, dp1, dx1);
    dx2 = fma(k, dp2, dx2);
  }
  d_x[3 * i + 0] = dx0;
  d_x[3 * i + 1] = dx1;
  d_x[3 * i + 2] = dx2;
}

// Zeroes count floats of buf from offset (the atomic path accumulates into a zeroed slice).
__kernel void field_hashgrid_zero(__global float* buf, const uint offset, const uint count) {
  const uint i = get_global_id(0);
  if (i < count) buf[offset + i] = 0.0f;
}
