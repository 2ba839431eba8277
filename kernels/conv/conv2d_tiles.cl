// 2-D convolution, the GPU-shaped variant (device profile gemm = "local_tiles", the "gpu"
// profile's): the same layouts, parameter slice and results as kernels/conv/conv2d.cl (+
// conv2d_narrow.cl), computed as implicit GEMMs by work-groups that stage tiles of the operands
// in local memory, each work-item keeping a BLK_R x BLK_C register block of scalar floats
// (kernels/common/gemm_tile.clh; conv2d.cl's work-items keep 8 x 16 floats in float16 vectors
// and 8 gathered pointers: right for PoCL's AVX-512 cores, spilled on a GPU). Any c_in / c_out:
// no narrow variants.
//
// Defines: conv2d.clh's (C_IN, IN_CS, IN_PAD, C_OUT, O_PAD, K, S, P) and, from the profile's
// gemm_* keys (runtime/conv/conv2d.cpp, runtime/cl/gemm_tiles.hpp), TILE_K (depth of a local
// tile), BLK_R, BLK_C and per kernel FWD_, BIN_, WGT_ + TC (columns of a tile) and LR (rows of
// work-items).
//
// Sums keep conv2d.cl's order (the forward: fma over the weight rows (ky, kx, c) in order from
// the bias, out-of-image taps adding fma(0, w, ·)), so the register block changes no bit.
#include "common/gemm_tile.clh"
#include "conv/conv2d.clh"

// Forward: the GEMM out[p][o] = bias[o] + Σ_r A[p][r] · W[r][o] over output pixels p =
// (n·HO + oy)·WO + ox and weight rows r = (ky·K + kx)·C_IN + c, A[p][r] = in[n, oy·S − P + ky,
// ox·S − P + kx, c] (0 outside the image). With `fuse_act` also act = leaky_relu(out, slope).
// Global (ceil(O_PAD / FWD_TC) · LC, ceil(pixels / TR) · FWD_LR).
#define FWD_LC (FWD_TC / BLK_C)
#define FWD_TR (FWD_LR * BLK_R)
#define FWD_WG (FWD_LC * FWD_LR)
__kernel __attribute__((reqd_work_group_size(FWD_LC, FWD_LR, 1))) void conv2d_fwd_tiles(
    const int n_img, const int H, const int W, const int HO, const int WO,
    __global const float* params, const uint w_off, __global const float* in,
    __global float* out, const int fuse_act, const float slope, __global float* act) {
  __local float a_tile[FWD_TR][TILE_K + 1];  // gathered input rows (+1: no bank conflicts)
  __local float w_tile[TILE_K][FWD_TC];
  __local int pix_img[FWD_TR], pix_y[FWD_TR], pix_x[FWD_TR];  // image offset, oy·S − P, ox·S − P
  const int lc = get_local_id(0), lr = get_local_id(1), lid = lr * FWD_LC + lc;
  const int c0 = get_group_id(0) * FWD_TC, p0 = get_group_id(1) * FWD_TR;
  const int n_pix = n_img * HO * WO;
  __global const float* Wg = params + w_off;
  for (int t = lid; t < FWD_TR; t += FWD_WG) {
    const int p = p0 + t;
    const int ox = p % WO, q = p / WO, oy = q % HO, n = q / HO;
    pix_img[t] = p < n_pix ? n * H * W * IN_CS : 0;
    pix_y[t] = p < n_pix ? oy * S - P : -K;  // -K: every tap outside
    pix_x[t] = ox * S - P;
  }
  float acc[BLK_R][BLK_C];
#pragma unroll
  for (int a = 0; a < BLK_R; ++a)
#pragma unroll
    for (int b = 0; b < BLK_C; ++b) {
      const int o = c0 + lc + FWD_LC * b;
      acc[a][b] = o < O_PAD ? Wg[N_ROWS * O_PAD + o] : 0.0f;
    }
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int k0 = 0; k0 < N_ROWS; k0 += TILE_K) {
    const int kn = min(TILE_K, N_ROWS - k0);
    for (int t = lid; t < FWD_TR * TILE_K; t += FWD_WG) {
      const int r = t / TILE_K, k = t % TILE_K;
      float v = 0.0f;
      if (k < kn) {
        const int row = k0 + k, tap = row / C_IN, c = row - tap * C_IN;
        const int iy = pix_y[r] + tap / K, ix = pix_x[r] + tap % K;
        if (iy >= 0 && iy < H && ix >= 0 && ix < W)
          v = in[(size_t)pix_img[r] + ((size_t)iy * W + ix) * IN_CS + c];
      }
      a_tile[r][k] = v;
    }
    for (int t = lid; t < TILE_K * FWD_TC; t += FWD_WG) {
      const int k = t / FWD_TC, c = t % FWD_TC;
      w_tile[k][c] = (k < kn && c0 + c < O_PAD) ? Wg[(size_t)(k0 + k) * O_PAD + c0 + c] : 0.0f;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
#define FWD_A(r, k) a_tile[r][k]
#define FWD_B(k, c) w_tile[k][c]
    GEMM_TILE_MAC(acc, kn, FWD_A, FWD_B, FWD_LR, FWD_LC, lr, lc);
    barrier(CLK_LOCAL_MEM_FENCE);
  }
#pragma unroll
  for (int a = 0; a < BLK_R; ++a) {
    const int p = p0 + lr + FWD_LR * a;
    if (p >= n_pix) continue;
#pragma unroll
    for (int b = 0; b < BLK_C; ++b) {
      const int o = c0 + lc + FWD_LC * b;
      if (o >= O_PAD) continue;
      const float v = acc[a][b];
      out[(size_t)p * O_PAD + o] = v;
      if (fuse_act) act[(size_t)p * O_PAD + o] = v > 0.0f ? v : v * slope;
    }
  }
}

// Input backward (a transposed convolution) as a GEMM per residue class: input pixels (iy, ix)
// with iy ≡ ry, ix ≡ rx (mod S) are read by the same taps (ky, kx) (those with S dividing
// iy + P − ky and ix + P − kx), so a tile of one class sums over those taps only:
// d_in[p][c] = Σ_{valid taps in (ky, kx) order} Σ_o d_out[n, oy, ox, o] · W[tap·C_IN + c][o],
// oy = (iy + P − ky) / S, ox = (ix + P − kx) / S (0 outside the output), conv2d.cl's order.
// Class pixels are enumerated as q = (n·HS + iy / S)·WS + ix / S (HS = ceil(H / S), WS =
// ceil(W / S)); W is read transposed into local memory (no transpose kernel). Writes the C_IN
// channels of d_in only. Global (ceil(IN_PAD / BIN_TC) · LC, S² · ceil(n·HS·WS / TR) · BIN_LR).
#define BIN_LC (BIN_TC / BLK_C)
#define BIN_TR (BIN_LR * BLK_R)
#define BIN_WG (BIN_LC * BIN_LR)
__kernel __attribute__((reqd_work_group_size(BIN_LC, BIN_LR, 1))) void conv2d_bwd_in_tiles(
    const int n_img, const int H, const int W, const int HO, const int WO,
    __global const float* params, const uint w_off, __global const float* d_out,
    __global float* d_in) {
  __local float d_tile[BIN_TR][TILE_K + 1];
  __local float w_tile[TILE_K][BIN_TC + 1];  // [output][input]: +1, the loads run down a column
  __local int pix_img[BIN_TR], pix_y[BIN_TR], pix_x[BIN_TR];  // n·HO·WO, iy, ix (iy -1: none)
  const int lc = get_local_id(0), lr = get_local_id(1), lid = lr * BIN_LC + lc;
  const int c0 = get_group_id(0) * BIN_TC;
  const int HS = (H + S - 1) / S, WS = (W + S - 1) / S;
  const int per_class = n_img * HS * WS, tiles = (per_class + BIN_TR - 1) / BIN_TR;
  const int cls = get_group_id(1) / tiles, p0 = (get_group_id(1) - cls * tiles) * BIN_TR;
  const int ry = cls / S, rx = cls % S;
  __global const float* Wg = params + w_off;
  for (int t = lid; t < BIN_TR; t += BIN_WG) {
    const int q = p0 + t;
    const int xs = q % WS, u = q / WS, ys = u % HS, n = u / HS;
    const int iy = ry + S * ys, ix = rx + S * xs;
    const int ok = q < per_class && iy < H && ix < W;
    pix_img[t] = n * HO * WO;
    pix_y[t] = ok ? iy : -1;
    pix_x[t] = ix;
  }
  float acc[BLK_R][BLK_C];
  GEMM_BLOCK_FILL(acc, 0.0f);
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int ky = 0; ky < K; ++ky) {
    if (((ry + P - ky) % S + S) % S != 0) continue;  // the same for the whole work-group
    for (int kx = 0; kx < K; ++kx) {
      if (((rx + P - kx) % S + S) % S != 0) continue;
      const int tap = ky * K + kx;
      for (int k0 = 0; k0 < C_OUT; k0 += TILE_K) {
        const int kn = min(TILE_K, C_OUT - k0);
        for (int t = lid; t < BIN_TR * TILE_K; t += BIN_WG) {
          const int r = t / TILE_K, k = t % TILE_K;
          float v = 0.0f;
          const int ty = pix_y[r] + P - ky, tx = pix_x[r] + P - kx;  // multiples of S
          if (k < kn && pix_y[r] >= 0 && ty >= 0 && tx >= 0) {
            const int oy = ty / S, ox = tx / S;
            if (oy < HO && ox < WO)
              v = d_out[((size_t)pix_img[r] + (size_t)oy * WO + ox) * O_PAD + k0 + k];
          }
          d_tile[r][k] = v;
        }
        for (int t = lid; t < BIN_TC * TILE_K; t += BIN_WG) {
          const int c = t / TILE_K, k = t % TILE_K, i = c0 + c;
          w_tile[k][c] =
              (k < kn && i < C_IN) ? Wg[((size_t)tap * C_IN + i) * O_PAD + k0 + k] : 0.0f;
        }
        barrier(CLK_LOCAL_MEM_FENCE);
#define BIN_A(r, k) d_tile[r][k]
#define BIN_B(k, c) w_tile[k][c]
        GEMM_TILE_MAC(acc, kn, BIN_A, BIN_B, BIN_LR, BIN_LC, lr, lc);
        barrier(CLK_LOCAL_MEM_FENCE);
      }
    }
  }
#pragma unroll
  for (int a = 0; a < BLK_R; ++a) {
    const int r = lr + BIN_LR * a;
    if (pix_y[r] < 0) continue;
    const size_t n = (size_t)(pix_img[r] / (HO * WO));
    __global float* dst = d_in + ((n * H + pix_y[r]) * W + pix_x[r]) * IN_CS;
#pragma unroll
    for (int b = 0; b < BLK_C; ++b) {
      const int c = c0 + lc + BIN_LC * b;
      if (c < C_IN) dst[c] = acc[a][b];
    }
  }
}

// Weight gradient, phase 1: partial[ch][r][o] = Σ_{output pixels p of chunk ch, in order}
// A[p][r] · d_out[p][o] with A = [im2col row, 1] (row N_ROWS is the bias row: Σ d_out), the
// pixels TILE_K at a time through local memory. Global (ceil(O_PAD / WGT_TC) · LC,
// ceil((N_ROWS + 1) / TR) · WGT_LR, chunks).
#define WGT_LC (WGT_TC / BLK_C)
#define WGT_TR (WGT_LR * BLK_R)
#define WGT_WG (WGT_LC * WGT_LR)
__kernel __attribute__((reqd_work_group_size(WGT_LC, WGT_LR, 1))) void conv2d_bwd_wgt_tiles(
    const int n_img, const int H, const int W, const int HO, const int WO, const int chunk,
    __global const float* in, __global const float* d_out, __global float* partial) {
  __local float a_tile[TILE_K][WGT_TR + 1];
  __local float d_tile[TILE_K][WGT_TC];
  __local int pix_img[TILE_K], pix_y[TILE_K], pix_x[TILE_K];  // as in the forward
  const int lc = get_local_id(0), lr = get_local_id(1), lid = lr * WGT_LC + lc;
  const int c0 = get_group_id(0) * WGT_TC, r0 = get_group_id(1) * WGT_TR;
  const int ch = get_group_id(2);
  const int n_pix = n_img * HO * WO;
  const int begin = ch * chunk, end = min(n_pix, begin + chunk);
  __global float* dst = partial + (size_t)ch * (N_ROWS + 1) * O_PAD;
  float acc[BLK_R][BLK_C];
  GEMM_BLOCK_FILL(acc, 0.0f);
  for (int q0 = begin; q0 < end; q0 += TILE_K) {
    const int kn = min(TILE_K, end - q0);
    for (int t = lid; t < TILE_K; t += WGT_WG) {
      const int p = q0 + t;
      const int ox = p % WO, q = p / WO, oy = q % HO, n = q / HO;
      pix_img[t] = t < kn ? n * H * W * IN_CS : 0;
      pix_y[t] = t < kn ? oy * S - P : -K;
      pix_x[t] = ox * S - P;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    for (int t = lid; t < TILE_K * WGT_TR; t += WGT_WG) {
      const int k = t / WGT_TR, r = t % WGT_TR, i = r0 + r;
      float v = 0.0f;
      if (k < kn) {
        if (i < N_ROWS) {
          const int tap = i / C_IN, c = i - tap * C_IN;
          const int iy = pix_y[k] + tap / K, ix = pix_x[k] + tap % K;
          if (iy >= 0 && iy < H && ix >= 0 && ix < W)
            v = in[(size_t)pix_img[k] + ((size_t)iy * W + ix) * IN_CS + c];
        } else if (i == N_ROWS) {
          v = 1.0f;  // fma(1, d, s) = s + d: the bias sum
        }
      }
      a_tile[k][r] = v;
    }
    for (int t = lid; t < TILE_K * WGT_TC; t += WGT_WG) {
      const int k = t / WGT_TC, c = t % WGT_TC, o = c0 + c;
      d_tile[k][c] = (k < kn && o < O_PAD) ? d_out[(size_t)(q0 + k) * O_PAD + o] : 0.0f;
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
      if (r <= N_ROWS && o < O_PAD) dst[(size_t)r * O_PAD + o] = acc[a][b];
    }
}

// Weight gradient, phase 2: grad[w_off + i] = Σ_ch partial[ch][i] (overwrites) in a fixed
// order (gemm_reduce_chunks: GEMM_REDUCE_LANES lanes, then a tree). Global
// (round_up((N_ROWS + 1) · O_PAD, 16), GEMM_REDUCE_LANES).
__kernel __attribute__((reqd_work_group_size(16, GEMM_REDUCE_LANES, 1))) void
conv2d_bwd_reduce_tiles(const int n_chunks, __global const float* partial, __global float* grad,
                        const uint w_off) {
  __local float sums[GEMM_REDUCE_LANES * 16];
  gemm_reduce_chunks(n_chunks, (N_ROWS + 1) * O_PAD, partial, grad, w_off, sums);
}
