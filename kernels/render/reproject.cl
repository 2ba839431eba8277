// Cross-frame reprojection (method.md §4.3): frame i's rendered range image, turned into points
// x_p = d_p·v_p in lidar i, moved into lidar j by T_lidarj_lidari and projected into frame j's
// range image keeping the nearest point per pixel (a z-buffer), and the backward pass of the
// range ||T_lidarj_lidari x_p|| to the depths and to the two poses.
//
// Determinism: the z-buffer runs in two passes of integer atomic_min (core OpenCL 1.1):
// pass 1 takes the minimum of the bits of q = ||y||² (positive floats order as their bits),
// pass 2 the smallest source index among the sources whose q bits equal that minimum. The
// result does not depend on scheduling. Pixels are chosen by sign tests against the pixel
// boundaries (geometry/pixel_boundaries.hpp), walking from a polynomial atan2 guess, so the
// choice (and the mask and winners) uses only IEEE multiplications, additions and comparisons
// and is the same on every device; contraction into FMA is off so that the host mirror
// (tests/render/reproject_reference.hpp) reproduces every bit. D_ij = √q is bit-identical
// where sqrt is correctly rounded (PoCL on x86; elsewhere it may differ in the last bit).
// Launchers: runtime/render/cross_frame_reprojection.cpp.

#pragma OPENCL FP_CONTRACT OFF

#define REPROJ_EMPTY_KEY 0xFFFFFFFFu
#define REPROJ_NO_WINNER 0x7FFFFFFF

#ifndef REPROJ_BWD_WG
#define REPROJ_BWD_WG 64
#endif

// y = R x + t with the rows (R_k0, R_k1, R_k2, t_k) of T_lidarj_lidari, in a fixed order.
inline float3 reproj_transform(const float4 m0, const float4 m1, const float4 m2, const float3 x) {
  return (float3)(m0.x * x.x + m0.y * x.y + m0.z * x.z + m0.w,
                  m1.x * x.x + m1.y * x.y + m1.z * x.z + m1.w,
                  m2.x * x.x + m2.y * x.y + m2.z * x.z + m2.w);
}

// Azimuth of (x, y) above column boundary k: cos b_k·y − sin b_k·x > 0.
inline int reproj_above_col(__global const float* col, const int k, const float x, const float y) {
  return col[2 * k] * y - col[2 * k + 1] * x > 0.0f;
}

// Elevation of a point with height z and horizontal distance² qxy above row boundary k
// (−1 ≤ k < H): cos e·z > sin e·√qxy, decided on squares so that no square root is needed.
inline int reproj_above_row(__global const float* row, const int k, const float z, const float qxy) {
  const float c = row[2 * (k + 1)], s = row[2 * (k + 1) + 1];
  const float a = z * c;
  const float b2 = qxy * (s * s);
  if (s > 0.0f) return a > 0.0f && a * a > b2;
  return a > 0.0f || a * a < b2;
}

// atan2 to within ~1e-5 rad (a minimax polynomial of atan on [0, 1]); only the first guess of
// a pixel uses it, the boundary tests decide.
inline float reproj_atan2_guess(const float y, const float x) {
  const float ax = fabs(x), ay = fabs(y);
  const float hi = fmax(ax, ay);
  const float a = hi > 0.0f ? fmin(ax, ay) / hi : 0.0f;
  const float s = a * a;
  float r = ((-0.0464964749f * s + 0.15931422f) * s - 0.327622764f) * s * a + a;
  if (ay > ax) r = M_PI_2_F - r;
  if (x < 0.0f) r = M_PI_F - r;
  return y < 0.0f ? -r : r;
}

// Column in [0, W] (W = outside): a guess of the protocol's rounding, then boundary tests walk
// to the column. The walk only ever goes one way, so it ends; where it ends does not depend on
// the guess as long as the guess is less than half a turn off (a boundary test is only valid
// within π of the boundary; the guess is off by ~1e-5 rad).
inline int reproj_column(__global const float* col, const int W, const float x, const float y) {
  const float u = (M_PI_F - reproj_atan2_guess(y, x)) * ((float)W / (2.0f * M_PI_F));
  int c = clamp((int)floor(u + 0.5f), 0, W);
  if (c < W && !reproj_above_col(col, c, x, y)) {
    do ++c;
    while (c < W && !reproj_above_col(col, c, x, y));
  } else {
    while (c > 0 && reproj_above_col(col, c - 1, x, y)) --c;
  }
  return c;
}

// Row in [−1, H] (−1 and H = outside the vertical field of view), as reproj_column (elevations
// differ by less than π, so any guess ends in the same row).
inline int reproj_row(__global const float* row, const int H, const float fov_up_rad,
                      const float inv_row_step, const float z, const float qxy) {
  const float alpha = reproj_atan2_guess(z, sqrt(qxy));
  int r = clamp((int)floor((fov_up_rad - alpha) * inv_row_step + 0.5f), -1, H);
  if (r < H && !reproj_above_row(row, r, z, qxy)) {
    do ++r;
    while (r < H && !reproj_above_row(row, r, z, qxy));
  } else {
    while (r > -1 && reproj_above_row(row, r - 1, z, qxy)) --r;
  }
  return r;
}

// Per target pixel: empty key and no winner; status[0] = no bad depth seen.
__kernel void render_reproject_fwd_clear(const int n_dst, __global uint* key, __global int* winner,
                                         __global int* status) {
  const int t = get_global_id(0);
  if (t == 0) {
    status[0] = REPROJ_NO_WINNER;
    status[1] = 0;
  }
  if (t >= n_dst) return;
  key[t] = REPROJ_EMPTY_KEY;
  winner[t] = REPROJ_NO_WINNER;
}

// Pass 1, per source pixel p: depth 0 = no depth; negative or non-finite depths are recorded
// (smallest such index in status[0]) and skipped. Points with q ≥ max_q or q ≤ min_q
// (range limits of sensor j, squared) or outside j's image are dropped. Writes the target
// pixel (−1 = none) and the key of p, and takes the minimum key per target pixel.
__kernel void render_reproject_fwd_zmin(
    const int n_src, __global const float* depth, __global const float* dirs, const float4 m0,
    const float4 m1, const float4 m2, const float min_q, const float max_q, const int H,
    const int W, const float fov_up_rad, const float inv_row_step, __global const float* col_tab,
    __global const float* row_tab, __global int* src_target, __global uint* src_key,
    __global volatile uint* key, __global volatile int* status) {
  const int p = get_global_id(0);
  if (p >= n_src) return;
  src_target[p] = -1;
  const float d = depth[p];
  if (!(d > 0.0f) || isinf(d)) {
    if (d != 0.0f) atomic_min(&status[0], p);
    return;
  }
  const float3 x = (float3)(d * dirs[3 * p], d * dirs[3 * p + 1], d * dirs[3 * p + 2]);
  const float3 y = reproj_transform(m0, m1, m2, x);
  const float qxy = y.x * y.x + y.y * y.y;
  const float q = qxy + y.z * y.z;
  if (q >= max_q || q <= min_q) return;
  const int r = reproj_row(row_tab, H, fov_up_rad, inv_row_step, y.z, qxy);
  if (r < 0 || r >= H) return;
  const int c = reproj_column(col_tab, W, y.x, y.y);
  if (c >= W) return;
  const int t = r * W + c;
  src_target[p] = t;
  src_key[p] = as_uint(q);
  atomic_min(&key[t], as_uint(q));
}

// Pass 2, per source pixel: the smallest index among the sources holding their pixel's
// minimum key wins. The first bad depth (status[0]) also has its value copied to status[1].
__kernel void render_reproject_fwd_winner(const int n_src, __global const float* depth,
                                          __global const int* src_target,
                                          __global const uint* src_key, __global const uint* key,
                                          __global volatile int* winner, __global int* status) {
  const int p = get_global_id(0);
  if (p >= n_src) return;
  if (p == status[0]) status[1] = as_int(depth[p]);
  const int t = src_target[p];
  if (t < 0) return;
  if (src_key[p] == key[t]) atomic_min(&winner[t], p);
}

// Pass 3, per target pixel: D_ij = √q of the winner, M_ij = 1; empty pixels 0, 0, winner −1.
__kernel void render_reproject_fwd_resolve(const int n_dst, __global const uint* key,
                                           __global int* winner, __global float* range,
                                           __global float* mask) {
  const int t = get_global_id(0);
  if (t >= n_dst) return;
  if (winner[t] == REPROJ_NO_WINNER) {
    winner[t] = -1;
    range[t] = 0.0f;
    mask[t] = 0.0f;
  } else {
    range[t] = sqrt(as_float(key[t]));
    mask[t] = 1.0f;
  }
}

// Zeroes the depth gradient of every source pixel (the backward writes only the winners).
__kernel void render_reproject_bwd_clear(const int n_src, __global float* grad_depth) {
  const int p = get_global_id(0);
  if (p < n_src) grad_depth[p] = 0.0f;
}

// Backward through the winners (the discrete pixel choice is not differentiated). For a target
// pixel with winner w and g = dL/dD: y = R x + t, r = ||y||, n = y/r, m = Rᵀn (n in lidar i);
// dL/dd_w = g·m·v_w (each source wins at most one pixel: plain stores, no race). The pose
// terms are reduced per work-group in a fixed order (strided slices of a contiguous chunk,
// then a fixed tree): partial[6g + 0..2] = Σ g·m, partial[6g + 3..5] = Σ g·(x × m).
__kernel void render_reproject_bwd(const int n_dst, const int chunk, __global const float* depth,
                                   __global const float* dirs, const float4 m0, const float4 m1,
                                   const float4 m2, __global const int* winner,
                                   __global const float* grad_range,
                                   __global float* grad_depth, __global float* partial) {
  __local float part[6][REPROJ_BWD_WG];
  const int lid = get_local_id(0), grp = get_group_id(0);
  const int begin = grp * chunk, end = min(begin + chunk, n_dst);
  float acc[6] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  for (int t = begin + lid; t < end; t += REPROJ_BWD_WG) {
    const int w = winner[t];
    if (w < 0) continue;
    const float g = grad_range[t], d = depth[w];
    const float3 v = (float3)(dirs[3 * w], dirs[3 * w + 1], dirs[3 * w + 2]);
    const float3 x = d * v;
    const float3 y = reproj_transform(m0, m1, m2, x);
    const float inv_r = 1.0f / sqrt(y.x * y.x + y.y * y.y + y.z * y.z);
    const float3 n = y * inv_r;
    const float3 m = (float3)(m0.x * n.x + m1.x * n.y + m2.x * n.z,
                              m0.y * n.x + m1.y * n.y + m2.y * n.z,
                              m0.z * n.x + m1.z * n.y + m2.z * n.z);
    grad_depth[w] = g * (m.x * v.x + m.y * v.y + m.z * v.z);
    const float3 xm = cross(x, m);
    acc[0] += g * m.x;
    acc[1] += g * m.y;
    acc[2] += g * m.z;
    acc[3] += g * xm.x;
    acc[4] += g * xm.y;
    acc[5] += g * xm.z;
  }
  for (int k = 0; k < 6; ++k) part[k][lid] = acc[k];
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int h = REPROJ_BWD_WG / 2; h > 0; h >>= 1) {
    if (lid < h)
      for (int k = 0; k < 6; ++k) part[k][lid] += part[k][lid + h];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0)
    for (int k = 0; k < 6; ++k) partial[6 * grp + k] = part[k][0];
}
