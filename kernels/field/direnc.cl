// View-direction frequency encoding (method.md §0 LiDAR head; torch-ngp FreqEncoder without the
// raw input) and the LiDAR-head input assembly, each with its backward.
//
// Encoding of ray r (unit direction d, 3 floats): enc[r*6F + k*6 + s*3 + j] =
// sin(2^k d_j) for s = 0 and cos(2^k d_j) for s = 1, k = 0..F-1 (F = N_FREQ, 12 → 72 dims).
#ifndef N_FREQ
#error "N_FREQ must be defined"
#endif
#define ENC_DIM (6 * N_FREQ)

__kernel void field_direnc_fwd(const int n_rays, __global const float* dir, __global float* enc) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const float3 d = vload3(r, dir);
  float f = 1.0f;
  for (int k = 0; k < N_FREQ; ++k) {
    float3 c;
    const float3 s = sincos(f * d, &c);
    vstore3(s, 0, enc + (size_t)r * ENC_DIM + k * 6);
    vstore3(c, 0, enc + (size_t)r * ENC_DIM + k * 6 + 3);
    f *= 2.0f;
  }
}

// d_dir_j = Σ_k 2^k (d_sin_kj cos(2^k d_j) − d_cos_kj sin(2^k d_j)).
__kernel void field_direnc_bwd(const int n_rays, __global const float* dir,
                               __global const float* d_enc, __global float* d_dir) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const float3 d = vload3(r, dir);
  float3 g = (float3)(0.0f);
  float f = 1.0f;
  for (int k = 0; k < N_FREQ; ++k) {
    float3 c;
    const float3 s = sincos(f * d, &c);
    const float3 ds = vload3(0, d_enc + (size_t)r * ENC_DIM + k * 6);
    const float3 dc = vload3(0, d_enc + (size_t)r * ENC_DIM + k * 6 + 3);
    g += f * (ds * c - dc * s);
    f *= 2.0f;
  }
  vstore3(g, r, d_dir);
}

// The same two under the gpu profile (device profile ray_work_items > 1; DirEncoding picks
// them): one ray's 12 frequencies are 12 work-items instead of one loop, so a batch of 4096
// rays launches 49 152 work-items rather than 4096. The forward is one work-item per (ray,
// frequency), the cpu kernel's loop body with f = 2^k exact. The backward is a work-group of
// DIRENC_WG work-items holding DIRENC_WG / DIRENC_LANES rays, DIRENC_LANES (N_FREQ rounded up
// to a power of two) lanes per ray; lane k computes frequency k's term (0 past N_FREQ) and the
// lanes are summed in a fixed tree in local memory: deterministic, not the cpu loop's order.
#define DIRENC_WG 64
#define DIRENC_LANES                                                                      \
  (N_FREQ <= 1 ? 1 : N_FREQ <= 2 ? 2 : N_FREQ <= 4 ? 4 : N_FREQ <= 8 ? 8 : N_FREQ <= 16 ? 16 \
                                                                                         : 32)
__kernel void field_direnc_fwd_wide(const int n_rays, __global const float* dir,
                                    __global float* enc) {
  const int i = get_global_id(0);
  if (i >= n_rays * N_FREQ) return;
  const int r = i / N_FREQ, k = i - r * N_FREQ;
  const float3 d = vload3(r, dir);
  const float f = (float)(1 << k);
  float3 c;
  const float3 s = sincos(f * d, &c);
  vstore3(s, 0, enc + (size_t)r * ENC_DIM + k * 6);
  vstore3(c, 0, enc + (size_t)r * ENC_DIM + k * 6 + 3);
}

// Launched as (DIRENC_LANES, rays rounded up to DIRENC_WG / DIRENC_LANES) in work-groups of
// (DIRENC_LANES, DIRENC_WG / DIRENC_LANES).
__kernel void field_direnc_bwd_wide(const int n_rays, __global const float* dir,
                                    __global const float* d_enc, __global float* d_dir) {
  __local float part[DIRENC_WG * 3];
  const int k = get_local_id(0), slot = get_local_id(1);
  const int r = get_global_id(1);
  float3 g = (float3)(0.0f);
  if (k < N_FREQ && r < n_rays) {
    const float3 d = vload3(r, dir);
    const float f = (float)(1 << k);
    float3 c;
    const float3 s = sincos(f * d, &c);
    const float3 ds = vload3(0, d_enc + (size_t)r * ENC_DIM + k * 6);
    const float3 dc = vload3(0, d_enc + (size_t)r * ENC_DIM + k * 6 + 3);
    g = f * (ds * c - dc * s);
  }
  __local float* mine = part + slot * DIRENC_LANES * 3;
  vstore3(g, k, mine);
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int h = DIRENC_LANES / 2; h > 0; h >>= 1) {
    if (k < h) vstore3(vload3(k, mine) + vload3(k + h, mine), k, mine);
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (k == 0 && r < n_rays) vstore3(vload3(0, mine), r, d_dir);
}

// head_in[n] = [dens[n, geo_start .. geo_start+n_geo), enc[n / samples]] for n < n_rays·samples.
__kernel void field_head_input_fwd(const int n, const int samples, const int n_geo,
                                   const int geo_start, const int dens_stride,
                                   __global const float* dens, __global const float* enc,
                                   __global float* head_in) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const int width = n_geo + ENC_DIM;
  __global float* dst = head_in + (size_t)i * width;
  __global const float* g = dens + (size_t)i * dens_stride + geo_start;
  for (int j = 0; j < n_geo; ++j) dst[j] = g[j];
  __global const float* e = enc + (size_t)(i / samples) * ENC_DIM;
  for (int j = 0; j < ENC_DIM; ++j) dst[n_geo + j] = e[j];
}

// Backward, geometric part: d_dens[n, geo_start + j] = d_head_in[n, j]; the other columns of
// d_dens (e.g. the density column the renderer fills) are left untouched.
__kernel void field_head_input_bwd_geo(const int n, const int n_geo, const int geo_start,
                                       const int dens_stride, __global const float* d_head_in,
                                       __global float* d_dens) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const int width = n_geo + ENC_DIM;
  for (int j = 0; j < n_geo; ++j)
    d_dens[(size_t)i * dens_stride + geo_start + j] = d_head_in[(size_t)i * width + j];
}

// Backward, direction part: d_enc[r, k] = Σ_{s = 0..samples−1, in order} d_head_in[r·S + s, n_geo + k].
// Work-item = (group of DIR_VEC encoding columns, ray): vector loads along the row.
#if ENC_DIM % 8 == 0
#define DIR_VEC 8
#define dirv float8
#define DIR_LOAD(p) vload8(0, p)
#define DIR_STORE(v, p) vstore8(v, 0, p)
#else
#define DIR_VEC 2
#define dirv float2
#define DIR_LOAD(p) vload2(0, p)
#define DIR_STORE(v, p) vstore2(v, 0, p)
#endif
__kernel void field_head_input_bwd_dir(const int n_rays, const int samples, const int n_geo,
                                       __global const float* d_head_in, __global float* d_enc) {
  const int k = get_global_id(0) * DIR_VEC;
  const int r = get_global_id(1);
  if (k >= ENC_DIM || r >= n_rays) return;
  const int width = n_geo + ENC_DIM;
  __global const float* src = d_head_in + (size_t)r * samples * width + n_geo + k;
  dirv s = (dirv)(0.0f);
  for (int t = 0; t < samples; ++t) s += DIR_LOAD(src + (size_t)t * width);
  DIR_STORE(s, d_enc + (size_t)r * ENC_DIM + k);
}
