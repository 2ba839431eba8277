// 2-D convolution kernels for outputs and inputs of 16 channels or more (vectors over output
// channels in the forward and the weight gradient, over input channels in the input backward).
// Layouts and defines: conv/conv2d.clh. Narrow shapes: conv/conv2d_narrow.cl.
#include "conv/conv2d.clh"

// Forward: out[n, oy, ox, :] = b + Σ_{ky,kx,c} in[n, oy·S − P + ky, ox·S − P + kx, c] · W[..],
// and with `fuse_act` also act[…] = leaky_relu(out, slope) (saves a pass over the output).
// Work-item = PTS consecutive output pixels of one row × 16 output channels.
// dim 0: tile = (n·HO + oy)·TX + tx with TX = ceil(WO / PTS); dim 1: output channel block.
__kernel void conv2d_fwd(const int n_img, const int H, const int W, const int HO, const int WO,
                         __global const float* params, const uint w_off,
                         __global const float* in, __global float* out,
                         __global const float* zeros, const int fuse_act, const float slope,
                         __global float* act) {
  const int TX = (WO + PTS - 1) / PTS;
  const int t = get_global_id(0);
  const int o0 = get_global_id(1) * 16;
  if (t >= n_img * HO * TX) return;
  const int row = t / TX;  // n·HO + oy
  const int ox0 = (t - row * TX) * PTS;
  const int n = row / HO, oy = row - n * HO;
  __global const float* Wg = params + w_off;
  float16 acc[PTS];
  const float16 b = vload16(0, Wg + N_ROWS * O_PAD + o0);
#pragma unroll
  for (int j = 0; j < PTS; ++j) acc[j] = b;
  for (int ky = 0; ky < K; ++ky) {
    const int iy = oy * S - P + ky;
    const int row_ok = iy >= 0 && iy < H;
    __global const float* in_row = in + (size_t)(n * H + iy) * W * IN_CS;
    for (int kx = 0; kx < K; ++kx) {
      __global const float* src[PTS];
      CONV_GATHER_TAP(src, in_row, row_ok, ox0, kx, zeros);
      __global const float* wrow = Wg + (size_t)(ky * K + kx) * C_IN * O_PAD + o0;
      for (int c = 0; c < C_IN; ++c) {
        const float16 w = vload16(0, wrow + c * O_PAD);
#pragma unroll
        for (int j = 0; j < PTS; ++j) acc[j] = fma((float16)(src[j][c]), w, acc[j]);
      }
    }
  }
#pragma unroll
  for (int j = 0; j < PTS; ++j) {
    if (ox0 + j >= WO) continue;
    const size_t at = ((size_t)row * WO + ox0 + j) * O_PAD + o0;
    vstore16(acc[j], 0, out + at);
    if (fuse_act) vstore16(select(acc[j] * slope, acc[j], acc[j] > (float16)(0.0f)), 0, act + at);
  }
}

// W transposed per tap for the input backward: wt[(tap·C_OUT + o)·IN_PAD + c] (zero padded).
__kernel void conv2d_transpose(__global const float* params, const uint w_off,
                               __global float* wt) {
  const int c = get_global_id(0);
  const int o = get_global_id(1);
  const int tap = get_global_id(2);
  if (c >= IN_PAD || o >= C_OUT || tap >= TAPS) return;
  wt[((size_t)tap * C_OUT + o) * IN_PAD + c] =
      c < C_IN ? params[w_off + ((size_t)tap * C_IN + c) * O_PAD + o] : 0.0f;
}

// Input backward (a transposed convolution): d_in[n, iy, ix, c] = Σ over the taps that read
// (iy, ix) of Σ_o d_out[n, oy, ox, o] · W[tap, c, o], with oy = (iy + P − ky) / S when that
// divides. A work-item takes PTS input pixels of one row spaced S apart (ix = r + S·m, same
// residue r), so every pixel of the tile uses the same taps and the inner loop has no branch.
// Work-item = PTS pixels × 16 input channels; dim 0: tile = ((n·H + iy)·S + r)·TXR + tx with
// TXR = ceil(ceil(W / S) / PTS); dim 1: input channel block. Overwrites d_in (its C_IN channels).
__kernel void conv2d_bwd_in(const int n_img, const int H, const int W, const int HO,
                            const int WO, __global const float* wt,
                            __global const float* d_out, __global float* d_in,
                            __global const float* zeros) {
  const int TXR = ((W + S - 1) / S + PTS - 1) / PTS;
  const int t = get_global_id(0);
  const int c0 = get_global_id(1) * 16;
  if (t >= n_img * H * S * TXR) return;
  const int tx = t % TXR;
  const int rr = t / TXR;  // (n·H + iy)·S + r
  const int r = rr % S;
  const int row = rr / S;  // n·H + iy
  const int n = row / H, iy = row - n * H;
  const int m0 = tx * PTS;
  float16 acc[PTS];
#pragma unroll
  for (int j = 0; j < PTS; ++j) acc[j] = (float16)(0.0f);
  for (int ky = 0; ky < K; ++ky) {
    const int ty = iy + P - ky;
    if (ty < 0 || ty % S != 0 || ty / S >= HO) continue;
    __global const float* dout_row = d_out + (size_t)(n * HO + ty / S) * WO * O_PAD;
    for (int kx = 0; kx < K; ++kx) {
      const int a = r + P - kx;  // ox = a / S + m when S divides a
      const int am = ((a % S) + S) % S;
      if (am != 0) continue;
      const int base = (a - am) / S;  // floor(a / S)
      __global const float* src[PTS];
#pragma unroll
      for (int j = 0; j < PTS; ++j) {
        const int ox = base + m0 + j;
        const int ix = r + S * (m0 + j);
        const int ok = ox >= 0 && ox < WO && ix < W;
        src[j] = ok ? dout_row + (size_t)ox * O_PAD : zeros;
      }
      __global const float* wrow = wt + (size_t)(ky * K + kx) * C_OUT * IN_PAD + c0;
      for (int o = 0; o < C_OUT; ++o) {
        const float16 w = vload16(0, wrow + o * IN_PAD);
#pragma unroll
        for (int j = 0; j < PTS; ++j) acc[j] = fma((float16)(src[j][o]), w, acc[j]);
      }
    }
  }
#pragma unroll
  for (int j = 0; j < PTS; ++j) {
    const int ix = r + S * (m0 + j);
    if (ix >= W) continue;
    __global float* dst = d_in + ((size_t)row * W + ix) * IN_CS;
#if IN_CS % 16 == 0
    vstore16(acc[j], 0, dst + c0);
#else
    float tmp[16];
    vstore16(acc[j], 0, tmp);
    for (int k = 0; k < 16; ++k)
      if (c0 + k < C_IN) dst[c0 + k] = tmp[k];
#endif
  }
}

// Weight gradient, phase 1: partial[ch] = Σ_{output pixels of chunk ch, in order}
// [im2col row, 1]ᵀ · d_out. Work-item = chunk × ROWS weight rows × 16 outputs; row block
// ROW_BLOCKS (the last) computes the bias row Σ d_out alone. Pixels are p = (n·HO + oy)·WO + ox.
#define ROW_BLOCKS ((N_ROWS + ROWS - 1) / ROWS)
__kernel void conv2d_bwd_wgt(const int n_img, const int H, const int W, const int HO,
                             const int WO, const int chunk, __global const float* in,
                             __global const float* d_out, __global float* partial) {
  const int ch = get_global_id(0);
  const int rb = get_global_id(1);
  const int o0 = get_global_id(2) * 16;
  if (rb > ROW_BLOCKS) return;
  const int n_pix = n_img * HO * WO;
  const int begin = ch * chunk, end = min(n_pix, begin + chunk);
  __global float* dst = partial + (size_t)ch * (N_ROWS + 1) * O_PAD;
  if (rb == ROW_BLOCKS) {
    float16 acc = (float16)(0.0f);
    for (int p = begin; p < end; ++p) acc += vload16(0, d_out + (size_t)p * O_PAD + o0);
    vstore16(acc, 0, dst + (size_t)N_ROWS * O_PAD + o0);
    return;
  }
  const int r0 = rb * ROWS;
  float16 acc[ROWS];
#pragma unroll
  for (int k = 0; k < ROWS; ++k) acc[k] = (float16)(0.0f);
  int ox = 0, oy = 0, n = 0;
  if (begin < end) {
    ox = begin % WO;
    oy = (begin / WO) % HO;
    n = begin / (WO * HO);
  }
#if C_IN % ROWS == 0 && ROWS == 16
  // Every row of the block belongs to one tap: one bounds check and contiguous channels.
  const int tap = r0 / C_IN, c0 = r0 % C_IN;
  const int dy = tap / K, dx = tap % K;
  for (int p = begin; p < end; ++p) {
    const float16 d = vload16(0, d_out + (size_t)p * O_PAD + o0);
    const int iy = oy * S - P + dy, ix = ox * S - P + dx;
    if (iy >= 0 && iy < H && ix >= 0 && ix < W) {
      // One vector load of the 16 input channels, broadcast lane by lane (ROWS == 16).
      const float16 a = vload16(0, in + ((size_t)(n * H + iy) * W + ix) * IN_CS + c0);
      acc[0] = fma((float16)(a.s0), d, acc[0]);
      acc[1] = fma((float16)(a.s1), d, acc[1]);
      acc[2] = fma((float16)(a.s2), d, acc[2]);
      acc[3] = fma((float16)(a.s3), d, acc[3]);
      acc[4] = fma((float16)(a.s4), d, acc[4]);
      acc[5] = fma((float16)(a.s5), d, acc[5]);
      acc[6] = fma((float16)(a.s6), d, acc[6]);
      acc[7] = fma((float16)(a.s7), d, acc[7]);
      acc[8] = fma((float16)(a.s8), d, acc[8]);
      acc[9] = fma((float16)(a.s9), d, acc[9]);
      acc[10] = fma((float16)(a.sa), d, acc[10]);
      acc[11] = fma((float16)(a.sb), d, acc[11]);
      acc[12] = fma((float16)(a.sc), d, acc[12]);
      acc[13] = fma((float16)(a.sd), d, acc[13]);
      acc[14] = fma((float16)(a.se), d, acc[14]);
      acc[15] = fma((float16)(a.sf), d, acc[15]);
    }
    if (++ox == WO) {
      ox = 0;
      if (++oy == HO) {
        oy = 0;
        ++n;
      }
    }
  }
#else
  // Rows of several taps (C_IN < ROWS or not a multiple): per-row tap offsets and bounds.
  int dy[ROWS], dx[ROWS], cc[ROWS];
#pragma unroll
  for (int k = 0; k < ROWS; ++k) {
    const int rk = min(r0 + k, N_ROWS - 1);  // rows past N_ROWS repeat the last; not stored
    const int tap = rk / C_IN;
    cc[k] = rk % C_IN;
    dy[k] = tap / K;
    dx[k] = tap % K;
  }
  for (int p = begin; p < end; ++p) {
    const float16 d = vload16(0, d_out + (size_t)p * O_PAD + o0);
    const int by = oy * S - P, bx = ox * S - P;
    __global const float* img = in + (size_t)n * H * W * IN_CS;
#pragma unroll
    for (int k = 0; k < ROWS; ++k) {
      const int iy = by + dy[k], ix = bx + dx[k];
      const float v = (iy >= 0 && iy < H && ix >= 0 && ix < W)
                          ? img[((size_t)iy * W + ix) * IN_CS + cc[k]]
                          : 0.0f;
      acc[k] = fma((float16)(v), d, acc[k]);
    }
    if (++ox == WO) {
      ox = 0;
      if (++oy == HO) {
        oy = 0;
        ++n;
      }
    }
  }
#endif
#pragma unroll
  for (int k = 0; k < ROWS; ++k)
    if (r0 + k < N_ROWS) vstore16(acc[k], 0, dst + (size_t)(r0 + k) * O_PAD + o0);
}

// Weight gradient, phase 2: grad[w_off + i] = Σ_ch partial[ch][i] in chunk order (overwrites).
__kernel void conv2d_bwd_reduce(const int n_chunks, __global const float* partial,
                                __global float* grad, const uint w_off) {
  const int i = get_global_id(0);
  const int count = (N_ROWS + 1) * O_PAD;
  if (i >= count) return;
  float s = 0.0f;
  for (int ch = 0; ch < n_chunks; ++ch) s += partial[(size_t)ch * count + i];
  grad[w_off + i] = s;
}
