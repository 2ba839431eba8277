// Ray casting of a baked scene (runtime/bake/ray_caster.hpp, docs/baking.md), one work-item per
// ray. Coarse to fine: a 3D DDA over the brick grid skips bricks that store nothing; inside a
// stored brick the ray takes samples on a lattice t_k = near + k·step (the same lattice in every
// brick, so a brick boundary neither repeats nor drops a sample), each a trilinear lookup of
// the brick's own (brick + 1)³ vertices (float4: σ logit per metre, return probability,
// intensity). Volume rendering as the field's renderer (kernels/render/volume.cl):
//   alpha_k = 1 − exp(−exp(logit_k)·step),  w_k = alpha_k Π_{j<k} (1 − alpha_j)
//   depth = Σ w_k t_k (not normalised), prob = Σ w_k p_k, intensity = Σ w_k i_k
// Early termination once the transmittance falls below stop_t. A sample in a cell whose 8
// vertices all have logit < skip_logit (it would stop less than the bake's min_alpha of the
// light) is skipped after one bit test of the brick's cell mask (cells x fastest, 32 a word),
// before its 8 gathers. out: n_rays × 10 (depth in metres, return probability, intensity,
// opacity Σ w_k, then the weight's quartile depths: the first sample depths t_k where the
// accumulated weight 1 − T reaches 1/8, 3/8, 5/8 and 7/8, −1 for a level not reached; then the
// median depth and the weight-normalised depth variance as the field's evaluation renders them
// (kernels/render/volume.cl: render_median_depth, render_depth_spread): the depth where T falls
// to 1/2, interpolated in its sample's interval with σ constant over it (the last sample's depth
// when never), and Σ w (t − m)² / Σ w, summed about the first weighted sample's depth). The
// quartiles let a renderer evaluate the field's head along the band the weight spreads over
// (pipeline::BakedRenderer) instead of at one point; the median and variance give it the
// evaluation's "median" and "mix" depths.
// Host reference: tests/bake/raycast_reference.hpp.

// Trilinear interpolation of the 8 vertices around local voxel coordinate u (0 ≤ u < brick)
// of the brick whose first vertex is verts[base].
inline float4 bake_trilinear(__global const float4* verts, int base, int n1, float3 u) {
  const int ix = (int)u.x, iy = (int)u.y, iz = (int)u.z;
  const float fx = u.x - (float)ix, fy = u.y - (float)iy, fz = u.z - (float)iz;
  const int v = base + (iz * n1 + iy) * n1 + ix, sz = n1 * n1;
  const float4 c00 = mix(verts[v], verts[v + 1], fx);
  const float4 c10 = mix(verts[v + n1], verts[v + n1 + 1], fx);
  const float4 c01 = mix(verts[v + sz], verts[v + sz + 1], fx);
  const float4 c11 = mix(verts[v + sz + n1], verts[v + sz + n1 + 1], fx);
  return mix(mix(c00, c10, fy), mix(c01, c11, fy), fz);
}

// 1/d per axis, a large finite value where d is 0 (no NaN from 0·inf).
inline float bake_inv(float d) { return fabs(d) > 1e-12f ? 1.0f / d : 1e30f; }

__kernel void bake_raycast(const int n_rays, __global const float* origins,
                           __global const float* dirs, const float4 lo, const float voxel,
                           const int4 dims, const int brick, const float near, const float far,
                           const float step, const float stop_t, __global const int* index,
                           __global const float4* verts, __global const uint* mask,
                           __global float* out) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const float ox = origins[3 * r] - lo.x, oy = origins[3 * r + 1] - lo.y,
              oz = origins[3 * r + 2] - lo.z;
  const float dx = dirs[3 * r], dy = dirs[3 * r + 1], dz = dirs[3 * r + 2];
  const float ix = bake_inv(dx), iy = bake_inv(dy), iz = bake_inv(dz);
  const float bm = voxel * (float)brick, inv_voxel = 1.0f / voxel;
  const int n1 = brick + 1, V = n1 * n1 * n1, words = (brick * brick * brick + 31) / 32;
  // The brick grid's box [0, dims·bm]: entry and exit.
  const float ax = -ox * ix, bx = ((float)dims.x * bm - ox) * ix;
  const float ay = -oy * iy, by = ((float)dims.y * bm - oy) * iy;
  const float az = -oz * iz, bz = ((float)dims.z * bm - oz) * iz;
  const float t0 = fmax(fmax(fmax(fmin(ax, bx), fmin(ay, by)), fmin(az, bz)), near);
  const float t1 = fmin(fmin(fmin(fmax(ax, bx), fmax(ay, by)), fmax(az, bz)), far);
  float depth = 0.0f, prob = 0.0f, inten = 0.0f, trans = 1.0f;
  float q[4] = {-1.0f, -1.0f, -1.0f, -1.0f};
  int lev = 0;  // levels reached
  // The median's crossing, and the moments about t_ref (the first weighted sample's depth).
  float median = -1.0f, last_t = 0.0f, t_ref = -1.0f, m1 = 0.0f, m2 = 0.0f;
  if (t0 < t1) {
    // The brick holding the entry point, and the DDA's next boundary per axis.
    int cx = clamp((int)floor((ox + dx * t0) / bm), 0, dims.x - 1);
    int cy = clamp((int)floor((oy + dy * t0) / bm), 0, dims.y - 1);
    int cz = clamp((int)floor((oz + dz * t0) / bm), 0, dims.z - 1);
    const int sx = dx >= 0.0f ? 1 : -1, sy = dy >= 0.0f ? 1 : -1, sz = dz >= 0.0f ? 1 : -1;
    float tx = ((float)(cx + (sx > 0)) * bm - ox) * ix;
    float ty = ((float)(cy + (sy > 0)) * bm - oy) * iy;
    float tz = ((float)(cz + (sz > 0)) * bm - oz) * iz;
    const float ddx = fabs(bm * ix), ddy = fabs(bm * iy), ddz = fabs(bm * iz);
    float tin = t0;
    bool live = true;
    while (live) {
      const float tout = fmin(fmin(fmin(tx, ty), tz), t1);
      const int slot = index[(cz * dims.y + cy) * dims.x + cx];
      if (slot >= 0) {
        const int base = slot * V;
        const float bx0 = (float)(cx * brick), by0 = (float)(cy * brick), bz0 = (float)(cz * brick);
        const float hi = (float)brick - 1e-3f;
        int k = (int)ceil((tin - near) / step);
        float t = near + (float)k * step;
        while (t < tout) {
          const float3 u = (float3)(clamp((ox + dx * t) * inv_voxel - bx0, 0.0f, hi),
                                    clamp((oy + dy * t) * inv_voxel - by0, 0.0f, hi),
                                    clamp((oz + dz * t) * inv_voxel - bz0, 0.0f, hi));
          const int cell = ((int)u.z * brick + (int)u.y) * brick + (int)u.x;
          if (!(mask[slot * words + (cell >> 5)] & (1u << (cell & 31)))) {
            ++k;
            t = near + (float)k * step;
            continue;
          }
          const float4 s = bake_trilinear(verts, base, n1, u);
          const float e = exp(-exp(fmin(s.x, 80.0f)) * step);
          const float w = trans * (1.0f - e);
          depth += w * t;
          prob += w * s.y;
          inten += w * s.z;
          if (t_ref < 0.0f) t_ref = t;
          m1 += w * (t - t_ref);
          m2 += w * (t - t_ref) * (t - t_ref);
          last_t = t;
          if (median < 0.0f && trans * e <= 0.5f) {
            const float tau = -log1p(-fmin(1.0f - e, 1.0f - 1e-7f));  // σ·step > 0
            median = t + fmin(fmax(log(2.0f * trans) / tau, 0.0f), 1.0f) * step;
          }
          trans *= e;
          while (lev < 4 && 1.0f - trans >= (float)(2 * lev + 1) * 0.125f) q[lev++] = t;
          if (trans < stop_t) {
            live = false;
            break;
          }
          ++k;
          t = near + (float)k * step;
        }
      }
      if (!live || tout >= t1) break;
      if (tx <= ty && tx <= tz) {
        cx += sx, tx += ddx;
        if (cx < 0 || cx >= dims.x) break;
      } else if (ty <= tz) {
        cy += sy, ty += ddy;
        if (cy < 0 || cy >= dims.y) break;
      } else {
        cz += sz, tz += ddz;
        if (cz < 0 || cz >= dims.z) break;
      }
      tin = tout;
    }
  }
  out[10 * r] = depth;
  out[10 * r + 1] = prob;
  out[10 * r + 2] = inten;
  out[10 * r + 3] = 1.0f - trans;
  for (int k = 0; k < 4; ++k) out[10 * r + 4 + k] = q[k];
  const float a = 1.0f - trans;
  float var = 0.0f;
  if (a >= 1e-12f) {
    const float mean = m1 / a;
    var = fmax(m2 / a - mean * mean, 0.0f);
  }
  out[10 * r + 8] = median >= 0.0f ? median : last_t;
  out[10 * r + 9] = var;
}
