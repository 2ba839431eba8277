// One fully connected layer of a small MLP, the GPU-shaped variant (device profile gemm =
// "local_tiles", runtime/cl/device_profile.hpp): the same layer, parameter layout, buffers and
// feature defines as kernels/field/mlp.cl (see its header: N_IN, IN_STRIDE, IN_OFFSET, IN_PAD,
// OUT, OUT_PAD, OUT_STRIDE, ACT, STORE_PRE, PREV_ACT, PREV_PRE, DIN_STRIDE, DIN_OFFSET,
// GROUP_BIAS, HAS_BIAS, TOWER_IN, TOWER_OUT), computed by work-groups that stage tiles of the
// operands in local memory, each work-item keeping a BLK_R x BLK_C register block of scalar
// floats (mlp.cl's work-items keep 8 x 16 floats in float16 vectors and read global memory
// directly: right for PoCL's AVX-512 cores, spilled registers and few work-items on a GPU).
// The register-block loop and the chunk tree are kernels/common/gemm_tile.clh's, shared with
// kernels/conv/conv2d_tiles.cl.
//
// Tile defines (runtime/cl/gemm_tiles.hpp, from the profile's gemm_* keys):
//   TILE_K: depth of a local tile (inputs in the forward, outputs in d_in, points in the
//   weight gradient); BLK_R, BLK_C: the register block (rows x columns); per kernel FWD_, BIN_,
//   WGT_ + TC (columns of the work-group's tile, a multiple of 16) and LR (work-items along the
//   rows). A work-group is LC = TC / BLK_C by LR work-items (dimension 0 along the columns, so
//   neighbouring work-items load and store neighbouring addresses) and covers TR = LR * BLK_R
//   rows; work-item (lc, lr) owns columns lc + LC * b and rows lr + LR * a.
//
// Every sum keeps mlp.cl's order (the forward and d_in: fma over the inputs / outputs in
// index order from the bias or zero; the weight gradient's chunk partials: fma over the
// chunk's points in order), so the tile shape changes no result: the host may pick a 1 x 1
// block for small launches. What differs from mlp.cl: the chunk partials are summed in a fixed
// tree (field_mlp_bwd_reduce) instead of in chunk order, the chunking is the profile's, and
// scalar math functions stand for the float16 ones; results agree with mlp.cl's to float
// rounding, and are bit-reproducible on one device. Towers: a tile whose columns lie in one
// tower skips the other towers' inputs as mlp.cl does (TOWER_OUT, resp. TOWER_IN for d_in, a
// multiple of the tile's TC); a tile across towers computes the dense product (the off-tower
// weights are zero, so the results are the same, only the work is not saved).
#include "common/gemm_tile.clh"
#include "field/mlp_layer.clh"

// mlp.cl's activations, per float.
inline float act_fwd(float z, int a) {
  if (a == ACT_RELU) return fmax(z, 0.0f);
  if (a == ACT_TANH) return tanh(z);
  if (a == ACT_SOFTPLUS) return log1p(exp(-fabs(z))) + fmax(z, 0.0f);
  if (a == ACT_SINE) return sin(z);
  return z;
}
// Derivative of the activation from its output y (relu, tanh, softplus, none).
inline float act_grad_post(float y, int a) {
  if (a == ACT_RELU) return y > 0.0f ? 1.0f : 0.0f;
  if (a == ACT_TANH) return 1.0f - y * y;
  if (a == ACT_SOFTPLUS) return -expm1(-y);
  return 1.0f;
}
// Derivative of the activation from its input z (every activation).
inline float act_grad_pre(float z, int a) {
  if (a == ACT_RELU) return z > 0.0f ? 1.0f : 0.0f;
  if (a == ACT_TANH) {
    const float t = tanh(z);
    return 1.0f - t * t;
  }
  if (a == ACT_SOFTPLUS) return 1.0f / (1.0f + exp(-z));
  if (a == ACT_SINE) return cos(z);
  return 1.0f;
}

// Forward: out = act(in · W_t + b) (GROUP_BIAS: + gbias[g] instead of b, g = point / group or
// gidx[point] when `indexed`). Global (ceil(OUT_PAD / TC) * LC, ceil(n / TR) * LR).
#define FWD_LC (FWD_TC / BLK_C)
#define FWD_TR (FWD_LR * BLK_R)
#define FWD_WG (FWD_LC * FWD_LR)
#define FWD_TOWER (TOWER_IN > 0 && TOWER_OUT > 0 && TOWER_OUT % FWD_TC == 0)
__kernel __attribute__((reqd_work_group_size(FWD_LC, FWD_LR, 1))) void field_mlp_fwd(
    const int n, __global const float* params, const uint w_off, __global const float* in,
    __global float* out, __global float* pre, __global const float* gbias, const int group,
    __global const int* gidx, const int indexed) {
  __local float a_tile[FWD_TR][TILE_K + 1];  // input rows (+1: no bank conflicts down k)
  __local float w_tile[TILE_K][FWD_TC];
  const int lc = get_local_id(0), lr = get_local_id(1), lid = lr * FWD_LC + lc;
  const int c0 = get_group_id(0) * FWD_TC, p0 = get_group_id(1) * FWD_TR;
  __global const float* W = params + w_off;
  float acc[BLK_R][BLK_C];
#pragma unroll
  for (int a = 0; a < BLK_R; ++a) {
#if GROUP_BIAS
    const int pp = min(p0 + lr + FWD_LR * a, n - 1);
    __global const float* gb = gbias + (size_t)(indexed ? gidx[pp] : pp / group) * OUT_PAD;
#endif
#pragma unroll
    for (int b = 0; b < BLK_C; ++b) {
      const int o = c0 + lc + FWD_LC * b;
#if GROUP_BIAS
      acc[a][b] = o < OUT_PAD ? gb[o] : 0.0f;
#elif HAS_BIAS
      acc[a][b] = o < OUT_PAD ? W[N_IN * OUT_PAD + o] : 0.0f;
#else
      acc[a][b] = 0.0f;
#endif
    }
  }
#if FWD_TOWER
  const int i_lo = (c0 / TOWER_OUT) * TOWER_IN, i_hi = min(N_IN, i_lo + TOWER_IN);
#else
  const int i_lo = 0, i_hi = N_IN;
#endif
  for (int k0 = i_lo; k0 < i_hi; k0 += TILE_K) {
    const int kn = min(TILE_K, i_hi - k0);
    for (int t = lid; t < FWD_TR * TILE_K; t += FWD_WG) {
      const int r = t / TILE_K, k = t % TILE_K, p = p0 + r;
      a_tile[r][k] = (p < n && k < kn) ? in[(size_t)p * IN_STRIDE + IN_OFFSET + k0 + k] : 0.0f;
    }
    for (int t = lid; t < TILE_K * FWD_TC; t += FWD_WG) {
      const int k = t / FWD_TC, c = t % FWD_TC;
      w_tile[k][c] = (k < kn && c0 + c < OUT_PAD) ? W[(k0 + k) * OUT_PAD + c0 + c] : 0.0f;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
#define FWD_A(r, k) a_tile[r][k]
#define FWD_B(k, c) w_tile[k][c]
    GEMM_TILE_MAC(acc, kn, FWD_A, FWD_B, FWD_LR, FWD_LC, lr, lc);
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  // Hidden layers (OUT_STRIDE = OUT_PAD) write their padding columns too, as mlp.cl does.
  const int width = OUT_STRIDE == OUT_PAD ? OUT_PAD : OUT;
#pragma unroll
  for (int a = 0; a < BLK_R; ++a) {
    const int p = p0 + lr + FWD_LR * a;
    if (p >= n) continue;
#pragma unroll
    for (int b = 0; b < BLK_C; ++b) {
      const int o = c0 + lc + FWD_LC * b;
#if STORE_PRE
      if (o < OUT_PAD) pre[(size_t)p * OUT_PAD + o] = acc[a][b];
#endif
      if (o < width) out[(size_t)p * OUT_STRIDE + o] = act_fwd(acc[a][b], ACT);
    }
  }
}

// Gradient at the pre-activation of the last layer: d_pre = d_out ⊙ act'(·), zero in the
// padding; one work-item per element of d_pre (n x OUT_PAD).
__kernel void field_mlp_bwd_out(const int n, __global const float* d_out, __global const float* y,
                                __global float* d_pre) {
  const size_t t = get_global_id(0);
  if (t >= (size_t)n * OUT_PAD) return;
  const size_t i = t / OUT_PAD;
  const int o = (int)(t % OUT_PAD);
  const float g = o < OUT ? d_out[i * OUT_STRIDE + o] : 0.0f;
#if ACT == ACT_NONE
  d_pre[t] = g;
#elif STORE_PRE
  d_pre[t] = g * act_grad_pre(o < OUT ? y[i * OUT_PAD + o] : 0.0f, ACT);
#else
  d_pre[t] = g * act_grad_post(o < OUT ? y[i * OUT_STRIDE + o] : 0.0f, ACT);
#endif
}

// Weight gradient, phase 1: partial[c][r][o] = Σ_{points p of chunk c, in order} A[p][r] ·
// d_pre[p][o] with A = [in, 1] (row N_IN is the bias row: Σ d_pre). Global (ceil(OUT_PAD / TC)
// * LC, ceil((N_IN + 1) / TR) * LR, chunks); each work-group walks its chunk TILE_K points at a
// time.
#define WGT_LC (WGT_TC / BLK_C)
#define WGT_TR (WGT_LR * BLK_R)
#define WGT_WG (WGT_LC * WGT_LR)
#define WGT_TOWER (TOWER_IN > 0 && TOWER_OUT > 0 && TOWER_OUT % WGT_TC == 0)
__kernel __attribute__((reqd_work_group_size(WGT_LC, WGT_LR, 1))) void field_mlp_bwd_wgt(
    const int n, const int chunk, __global const float* in, __global const float* d_pre,
    __global float* partial) {
  __local float a_tile[TILE_K][WGT_TR + 1];
  __local float d_tile[TILE_K][WGT_TC];
  const int lc = get_local_id(0), lr = get_local_id(1), lid = lr * WGT_LC + lc;
  const int c0 = get_group_id(0) * WGT_TC, r0 = get_group_id(1) * WGT_TR;
  const int ch = get_group_id(2);
  const int begin = ch * chunk, end = min(n, begin + chunk);
  __global float* dst = partial + (size_t)ch * (N_IN + 1) * OUT_PAD;
#if WGT_TOWER
  {  // A row tile wholly outside this column tile's tower (and not the bias row): zeros, as
     // field_mlp_tower_mask leaves them. The same for the whole work-group.
    const int t_lo = (c0 / TOWER_OUT) * TOWER_IN, r_hi = min(r0 + WGT_TR, N_IN + 1);
    if (r_hi <= N_IN && (r_hi <= t_lo || r0 >= t_lo + TOWER_IN)) {
      for (int a = 0; a < BLK_R; ++a)
        for (int b = 0; b < BLK_C; ++b) {
          const int r = r0 + lr + WGT_LR * a, o = c0 + lc + WGT_LC * b;
          if (r < r_hi && o < OUT_PAD) dst[(size_t)r * OUT_PAD + o] = 0.0f;
        }
      return;
    }
  }
#endif
  float acc[BLK_R][BLK_C];
  GEMM_BLOCK_FILL(acc, 0.0f);
  for (int q0 = begin; q0 < end; q0 += TILE_K) {
    const int kn = min(TILE_K, end - q0);
    for (int t = lid; t < TILE_K * WGT_TR; t += WGT_WG) {
      const int k = t / WGT_TR, r = t % WGT_TR, i = r0 + r;
      float v = 0.0f;
      if (k < kn) {
        if (i < N_IN) v = in[(size_t)(q0 + k) * IN_STRIDE + IN_OFFSET + i];
        else if (i == N_IN) v = 1.0f;  // fma(1, d, s) = s + d: mlp.cl's bias sum
      }
      a_tile[k][r] = v;
    }
    for (int t = lid; t < TILE_K * WGT_TC; t += WGT_WG) {
      const int k = t / WGT_TC, c = t % WGT_TC, o = c0 + c;
      d_tile[k][c] = (k < kn && o < OUT_PAD) ? d_pre[(size_t)(q0 + k) * OUT_PAD + o] : 0.0f;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
#define WGT_A(r, k) a_tile[k][r]
#define WGT_B(k, c) d_tile[k][c]
    GEMM_TILE_MAC(acc, kn, WGT_A, WGT_B, WGT_LR, WGT_LC, lr, lc);
    barrier(CLK_LOCAL_MEM_FENCE);
  }
#pragma unroll
  for (int a = 0; a < BLK_R; ++a)
#pragma unroll
    for (int b = 0; b < BLK_C; ++b) {
      const int r = r0 + lr + WGT_LR * a, o = c0 + lc + WGT_LC * b;
      if (r <= N_IN && o < OUT_PAD)
        dst[(size_t)r * OUT_PAD + o] = (!HAS_BIAS && r == N_IN) ? 0.0f : acc[a][b];
    }
}

// Weight gradient, phase 2: grad[w_off + k] = Σ_c partial[c][k] (overwrites), in a fixed
// order (gemm_reduce_chunks: lane l of GEMM_REDUCE_LANES sums chunks l, l + LANES, ... in
// order, then the lanes add in a fixed tree). Global (round_up((N_IN + 1) * OUT_PAD, 16),
// GEMM_REDUCE_LANES).
__kernel __attribute__((reqd_work_group_size(16, GEMM_REDUCE_LANES, 1))) void
field_mlp_bwd_reduce(const int n_chunks, __global const float* partial, __global float* grad,
                     const uint w_off) {
  __local float sums[GEMM_REDUCE_LANES * 16];
  gemm_reduce_chunks(n_chunks, (N_IN + 1) * OUT_PAD, partial, grad, w_off, sums);
}

// Input backward: d_in = d_pre · W (W_t read transposed into local memory: no transpose
// kernel). With PREV_ACT >= 0 the previous layer's activation derivative is applied (prev =
// its output, stride IN_STRIDE, or its pre-activation with PREV_PRE), giving that layer's d_pre
// (stride IN_PAD, padding columns zero); with PREV_ACT < 0 (the MLP's input) only the N_IN
// columns at DIN_OFFSET of each DIN_STRIDE row are written. Global (ceil(IN_PAD / TC) * LC,
// ceil(n / TR) * LR).
#define BIN_LC (BIN_TC / BLK_C)
#define BIN_TR (BIN_LR * BLK_R)
#define BIN_WG (BIN_LC * BIN_LR)
#define BIN_TOWER (TOWER_IN > 0 && TOWER_OUT > 0 && TOWER_IN % BIN_TC == 0)
__kernel __attribute__((reqd_work_group_size(BIN_LC, BIN_LR, 1))) void field_mlp_bwd_in(
    const int n, __global const float* params, const uint w_off, __global const float* d_pre,
    __global const float* prev, __global float* d_in) {
  __local float d_tile[BIN_TR][TILE_K + 1];
  __local float w_tile[TILE_K][BIN_TC + 1];  // [output][input]: +1, the loads run down a column
  const int lc = get_local_id(0), lr = get_local_id(1), lid = lr * BIN_LC + lc;
  const int c0 = get_group_id(0) * BIN_TC, p0 = get_group_id(1) * BIN_TR;
  __global const float* W = params + w_off;
  float acc[BLK_R][BLK_C];
  GEMM_BLOCK_FILL(acc, 0.0f);
#if BIN_TOWER
  const int o_lo = (c0 / TOWER_IN) * TOWER_OUT, o_hi = min(OUT, o_lo + TOWER_OUT);
#else
  const int o_lo = 0, o_hi = OUT;
#endif
  for (int k0 = o_lo; k0 < o_hi; k0 += TILE_K) {
    const int kn = min(TILE_K, o_hi - k0);
    for (int t = lid; t < BIN_TR * TILE_K; t += BIN_WG) {
      const int r = t / TILE_K, k = t % TILE_K, p = p0 + r;
      d_tile[r][k] = (p < n && k < kn) ? d_pre[(size_t)p * OUT_PAD + k0 + k] : 0.0f;
    }
    for (int t = lid; t < BIN_TC * TILE_K; t += BIN_WG) {
      const int c = t / TILE_K, k = t % TILE_K, i = c0 + c;
      w_tile[k][c] = (k < kn && i < N_IN) ? W[i * OUT_PAD + k0 + k] : 0.0f;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
#define BIN_A(r, k) d_tile[r][k]
#define BIN_B(k, c) w_tile[k][c]
    GEMM_TILE_MAC(acc, kn, BIN_A, BIN_B, BIN_LR, BIN_LC, lr, lc);
    barrier(CLK_LOCAL_MEM_FENCE);
  }
#pragma unroll
  for (int a = 0; a < BLK_R; ++a) {
    const int p = p0 + lr + BIN_LR * a;
    if (p >= n) continue;
    const size_t row = (size_t)p;
#pragma unroll
    for (int b = 0; b < BLK_C; ++b) {
      const int i = c0 + lc + BIN_LC * b;
#if PREV_ACT < 0
      if (i < N_IN) d_in[row * DIN_STRIDE + DIN_OFFSET + i] = acc[a][b];
#elif PREV_ACT == ACT_NONE
      if (i < IN_PAD) d_in[row * IN_PAD + i] = acc[a][b];
#elif PREV_PRE
      if (i < IN_PAD)
        d_in[row * IN_PAD + i] = acc[a][b] * act_grad_pre(prev[row * IN_PAD + i], PREV_ACT);
#else
      if (i < IN_PAD)
        d_in[row * IN_PAD + i] = acc[a][b] * act_grad_post(prev[row * IN_STRIDE + i], PREV_ACT);
#endif
    }
  }
}

// Grouped inputs, backward: d_group[g][o] = Σ_{k in group g, in order} d_pre[k][o] (mlp.cl's
// sums, one work-item per (group, column) instead of per (group, 16 columns)); group g holds
// points [g·group, (g + 1)·group), or [goff[g], goff[g + 1]) when `indexed`.
__kernel void field_mlp_group_sum(const int n_groups, const int group,
                                  __global const float* d_pre, __global float* d_group,
                                  __global const int* goff, const int indexed) {
  const size_t t = get_global_id(0);
  if (t >= (size_t)n_groups * OUT_PAD) return;
  const int g = (int)(t / OUT_PAD), o = (int)(t % OUT_PAD);
  const int k0 = indexed ? goff[g] : g * group, k1 = indexed ? goff[g + 1] : (g + 1) * group;
  float acc = 0.0f;
  for (int k = k0; k < k1; ++k) acc += d_pre[(size_t)k * OUT_PAD + o];
  d_group[t] = acc;
}

// Towers: zeroes the gradient of the structurally zero off-tower weights (as mlp.cl).
__kernel void field_mlp_tower_mask(const int count, __global const uchar* keep,
                                   __global float* grad, const uint g_off) {
  const int k = get_global_id(0);
  if (k < count && !keep[k]) grad[g_off + k] = 0.0f;
}
