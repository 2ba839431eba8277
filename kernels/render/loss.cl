// Range loss (method.md §0) and LiDAR-NeRF's range-image gradient loss on patches, each
// writing per-ray terms and dL/d(depth, prob, intensity) of the batch mean, plus a fixed-order
// single-work-group reduction of the per-ray terms (deterministic on every device).
// out and target are n_rays x 3: (depth, return prob, intensity) and (range, intensity,
// return label). Host references: tests/render/render_reference.hpp.

#ifndef RENDER_REDUCE_WG
#define RENDER_REDUCE_WG 256
#endif

inline float render_sign(float v) { return v > 0.0f ? 1.0f : (v < 0.0f ? -1.0f : 0.0f); }

// Per ray r with mask m = label (GT return):
//   depth  a_d |m (D - R)|,  return  a_r (P - clamp(m, s, 1 - s))^2,  intensity  a_i (m (I - I*))^2
// with the ray-drop label smoothing s (LiDAR4D; 0: the label itself).
// terms (n x 3) gets the three weighted terms; grad_out = inv_n * their derivatives
// (gradient of the batch mean; inv_n = 1 / n_rays).
__kernel void render_loss_range(const int n_rays, const float a_d, const float a_r, const float a_i,
                                const float smooth, const float inv_n, __global const float* out,
                                __global const float* target, __global float* terms,
                                __global float* grad_out) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const float m = target[3 * r + 2];
  const float e_d = m * (out[3 * r] - target[3 * r]);
  const float e_r = out[3 * r + 1] - clamp(m, smooth, 1.0f - smooth);
  const float e_i = m * (out[3 * r + 2] - target[3 * r + 1]);
  terms[3 * r + 0] = a_d * fabs(e_d);
  terms[3 * r + 1] = a_r * e_r * e_r;
  terms[3 * r + 2] = a_i * e_i * e_i;
  grad_out[3 * r + 0] = inv_n * a_d * m * render_sign(e_d);
  grad_out[3 * r + 1] = inv_n * 2.0f * a_r * e_r;
  grad_out[3 * r + 2] = inv_n * 2.0f * a_i * m * e_i;
}

// Masked difference error of the pair (a, b) of neighbouring pixels (b right of or below a):
// depth differences in metres (x inv_scale); the pair counts when both have a GT return and
// the GT difference is below clip (LiDAR-NeRF keeps smooth surfaces only).
inline float render_pair_error(__global const float* out, __global const float* target, int a,
                               int b, float inv_scale, float clip, float* mask) {
  const float dg = (target[3 * b] - target[3 * a]) * inv_scale;
  const float dp = (out[3 * b] - out[3 * a]) * inv_scale;
  *mask = target[3 * a + 2] * target[3 * b + 2] * (fabs(dg) < clip ? 1.0f : 0.0f);
  return *mask * (dp - dg);
}

// Per-pair penalty rho(e) = |e| (l1 != 0, LiDAR-NeRF's default) or e^2, and rho'(e).
inline float render_rho(float e, int l1) { return l1 ? fabs(e) : e * e; }
inline float render_drho(float e, int l1) { return l1 ? render_sign(e) : 2.0f * e; }

// Rays are patch-major: patch p's pixel (row, col) is ray p*R*C + row*C + col for patches of
// R rows x C columns. The loss is a_g * mean over all horizontal and vertical pairs of
// rho(e) (inv_pairs = 1 / (n_patches (R (C-1) + (R-1) C)); masked pairs count as zero).
// terms[r] = a_g * rho of the pairs that start at r (right and down); grad_out[3r] +=
// inv_pairs * dL/dD_r (accumulates onto the range loss's gradient).
__kernel void render_loss_patchgrad(const int n_rays, const int rows, const int cols, const int l1,
                                    const float a_g, const float inv_scale, const float clip,
                                    const float inv_pairs, __global const float* out,
                                    __global const float* target, __global float* terms,
                                    __global float* grad_out) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const int q = r % (rows * cols), row = q / cols, col = q % cols;
  float m, e, loss = 0.0f, g = 0.0f;
  if (col + 1 < cols) {
    e = render_pair_error(out, target, r, r + 1, inv_scale, clip, &m);
    loss += render_rho(e, l1);
    g -= render_drho(e, l1) * m;
  }
  if (row + 1 < rows) {
    e = render_pair_error(out, target, r, r + cols, inv_scale, clip, &m);
    loss += render_rho(e, l1);
    g -= render_drho(e, l1) * m;
  }
  if (col > 0) {
    e = render_pair_error(out, target, r - 1, r, inv_scale, clip, &m);
    g += render_drho(e, l1) * m;
  }
  if (row > 0) {
    e = render_pair_error(out, target, r - cols, r, inv_scale, clip, &m);
    g += render_drho(e, l1) * m;
  }
  terms[r] = a_g * loss;
  grad_out[3 * r] += inv_pairs * a_g * inv_scale * g;
}

// out[out_index] = scale * sum_{i<n} in[offset + i*stride], with one work-group of
// RENDER_REDUCE_WG items: each sums a strided slice in index order, then a fixed tree.
__kernel void render_loss_reduce(const int n, const int stride, const int offset, const float scale,
                                 __global const float* in, __global float* out,
                                 const int out_index) {
  __local float partial[RENDER_REDUCE_WG];
  const int lid = get_local_id(0);
  float acc = 0.0f;
  for (int i = lid; i < n; i += RENDER_REDUCE_WG) acc += in[offset + i * stride];
  partial[lid] = acc;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int h = RENDER_REDUCE_WG / 2; h > 0; h >>= 1) {
    if (lid < h) partial[lid] += partial[lid + h];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0) out[out_index] = scale * partial[0];
}
