// 2-D convolution kernels for narrow shapes, where vectors over the other channel dimension
// fill the 16 lanes: outputs c_out <= 2 (forward, weight gradient) and inputs c_in <= 4 (input
// backward). Same layouts, defines and results as conv/conv2d.cl.
#include "conv/conv2d.clh"

// Narrow outputs (C_OUT <= 2, e.g. the PatchGAN's logit layer or a U-Net's 1-channel head): the
// wide kernels would compute 16 padded output lanes for one useful one, so these vectorise over
// 16 input channels instead (C_IN and IN_CS multiples of 16). Same layouts and results.
#if C_OUT <= 2 && C_IN % 16 == 0 && IN_CS % 16 == 0

// Forward: work-item = PTS consecutive output pixels of one row × all outputs; the weights come
// transposed per tap (conv2d_transpose: wt[(tap·C_OUT + o)·IN_PAD + c]). Writes every channel
// of the output row (padding 0). dim 0 as conv2d_fwd; no channel-block dimension.
__kernel void conv2d_fwd_narrow(const int n_img, const int H, const int W, const int HO,
                                const int WO, __global const float* params, const uint w_off,
                                __global const float* wt, __global const float* in,
                                __global float* out, __global const float* zeros,
                                const int fuse_act, const float slope, __global float* act) {
  const int TX = (WO + PTS - 1) / PTS;
  const int t = get_global_id(0);
  if (t >= n_img * HO * TX) return;
  const int row = t / TX;
  const int ox0 = (t - row * TX) * PTS;
  const int n = row / HO, oy = row - n * HO;
  float16 acc[PTS][C_OUT];
#pragma unroll
  for (int j = 0; j < PTS; ++j)
#pragma unroll
    for (int o = 0; o < C_OUT; ++o) acc[j][o] = (float16)(0.0f);
  for (int ky = 0; ky < K; ++ky) {
    const int iy = oy * S - P + ky;
    const int row_ok = iy >= 0 && iy < H;
    __global const float* in_row = in + (size_t)(n * H + iy) * W * IN_CS;
    for (int kx = 0; kx < K; ++kx) {
      __global const float* src[PTS];
      CONV_GATHER_TAP(src, in_row, row_ok, ox0, kx, zeros);
      __global const float* wtap = wt + (size_t)(ky * K + kx) * C_OUT * IN_PAD;
      for (int c0 = 0; c0 < C_IN; c0 += 16) {
#pragma unroll
        for (int o = 0; o < C_OUT; ++o) {
          const float16 w = vload16(0, wtap + o * IN_PAD + c0);
#pragma unroll
          for (int j = 0; j < PTS; ++j) acc[j][o] = fma(vload16(0, src[j] + c0), w, acc[j][o]);
        }
      }
    }
  }
  __global const float* bias = params + w_off + N_ROWS * O_PAD;
#pragma unroll
  for (int j = 0; j < PTS; ++j) {
    if (ox0 + j >= WO) continue;
    const size_t at = ((size_t)row * WO + ox0 + j) * O_PAD;
    for (int o = 0; o < O_PAD; ++o) {
      float v = 0.0f;
#pragma unroll
      for (int q = 0; q < C_OUT; ++q)
        if (q == o) v = bias[o] + conv_hsum16(acc[j][q]);
      out[at + o] = v;
      if (fuse_act) act[at + o] = v > 0.0f ? v : slope * v;
    }
  }
}

// Weight gradient, phase 1, narrow outputs: work-item = chunk × (tap, 16 input channels); the
// last index (TAPS · C_IN / 16) computes the bias row. Fills whole partial rows (padding 0) so
// conv2d_bwd_reduce applies unchanged.
__kernel void conv2d_bwd_wgt_narrow(const int n_img, const int H, const int W, const int HO,
                                    const int WO, const int chunk, __global const float* in,
                                    __global const float* d_out, __global float* partial) {
  const int ch = get_global_id(0);
  const int g = get_global_id(1);
  const int CB = C_IN / 16;
  if (g > TAPS * CB) return;
  const int n_pix = n_img * HO * WO;
  const int begin = ch * chunk, end = min(n_pix, begin + chunk);
  __global float* dst = partial + (size_t)ch * (N_ROWS + 1) * O_PAD;
  if (g == TAPS * CB) {
    float b[C_OUT];
#pragma unroll
    for (int o = 0; o < C_OUT; ++o) b[o] = 0.0f;
    for (int p = begin; p < end; ++p)
#pragma unroll
      for (int o = 0; o < C_OUT; ++o) b[o] += d_out[(size_t)p * O_PAD + o];
    for (int o = 0; o < O_PAD; ++o) {
      float v = 0.0f;
#pragma unroll
      for (int q = 0; q < C_OUT; ++q)
        if (q == o) v = b[q];
      dst[(size_t)N_ROWS * O_PAD + o] = v;
    }
    return;
  }
  const int tap = g / CB, c0 = (g - tap * CB) * 16;
  const int dy = tap / K, dx = tap % K;
  float16 acc[C_OUT];
#pragma unroll
  for (int o = 0; o < C_OUT; ++o) acc[o] = (float16)(0.0f);
  int ox = 0, oy = 0, n = 0;
  if (begin < end) {
    ox = begin % WO;
    oy = (begin / WO) % HO;
    n = begin / (WO * HO);
  }
  for (int p = begin; p < end; ++p) {
    const int iy = oy * S - P + dy, ix = ox * S - P + dx;
    if (iy >= 0 && iy < H && ix >= 0 && ix < W) {
      const float16 a = vload16(0, in + ((size_t)(n * H + iy) * W + ix) * IN_CS + c0);
#pragma unroll
      for (int o = 0; o < C_OUT; ++o) acc[o] = fma(a, (float16)(d_out[(size_t)p * O_PAD + o]), acc[o]);
    }
    if (++ox == WO) {
      ox = 0;
      if (++oy == HO) {
        oy = 0;
        ++n;
      }
    }
  }
  float v[C_OUT][16];
#pragma unroll
  for (int o = 0; o < C_OUT; ++o) vstore16(acc[o], 0, v[o]);
  for (int k = 0; k < 16; ++k) {
    __global float* r = dst + (size_t)(tap * C_IN + c0 + k) * O_PAD;
    for (int o = 0; o < O_PAD; ++o) {
      float x = 0.0f;
#pragma unroll
      for (int q = 0; q < C_OUT; ++q)
        if (q == o) x = v[q][k];
      r[o] = x;
    }
  }
}
#endif

// Input backward for narrow inputs (C_IN <= 4, e.g. the 2-channel [D_ij, D_j] pair): the wide
// kernel would fill 16 lanes of input channels for 2 useful ones, so this one vectorises over
// output channels, d_in[c] = Σ_tap hsum(d_out[p'][o-block] · W[tap][c][o-block]), straight from
// the parameter layout (no transpose). Work-item = PTS input pixels (same residue, as in
// conv2d_bwd_in) × all C_IN channels; dim 0 as conv2d_bwd_in, no channel-block dimension.
#if C_IN <= 4
__kernel void conv2d_bwd_in_narrow(const int n_img, const int H, const int W, const int HO,
                                   const int WO, __global const float* params, const uint w_off,
                                   __global const float* d_out, __global float* d_in,
                                   __global const float* zeros) {
  const int TXR = ((W + S - 1) / S + PTS - 1) / PTS;
  const int t = get_global_id(0);
  if (t >= n_img * H * S * TXR) return;
  const int tx = t % TXR;
  const int rr = t / TXR;
  const int r = rr % S;
  const int row = rr / S;
  const int n = row / H, iy = row - n * H;
  const int m0 = tx * PTS;
  __global const float* Wg = params + w_off;
  float16 acc[PTS][C_IN];
#pragma unroll
  for (int j = 0; j < PTS; ++j)
#pragma unroll
    for (int c = 0; c < C_IN; ++c) acc[j][c] = (float16)(0.0f);
  for (int ky = 0; ky < K; ++ky) {
    const int ty = iy + P - ky;
    if (ty < 0 || ty % S != 0 || ty / S >= HO) continue;
    __global const float* dout_row = d_out + (size_t)(n * HO + ty / S) * WO * O_PAD;
    for (int kx = 0; kx < K; ++kx) {
      const int a = r + P - kx;
      const int am = ((a % S) + S) % S;
      if (am != 0) continue;
      const int base = (a - am) / S;
      __global const float* src[PTS];
#pragma unroll
      for (int j = 0; j < PTS; ++j) {
        const int ox = base + m0 + j;
        const int ix = r + S * (m0 + j);
        const int ok = ox >= 0 && ox < WO && ix < W;
        src[j] = ok ? dout_row + (size_t)ox * O_PAD : zeros;
      }
      __global const float* wtap = Wg + (size_t)(ky * K + kx) * C_IN * O_PAD;
      for (int o0 = 0; o0 < O_PAD; o0 += 16) {
        float16 w[C_IN];
#pragma unroll
        for (int c = 0; c < C_IN; ++c) w[c] = vload16(0, wtap + c * O_PAD + o0);
#pragma unroll
        for (int j = 0; j < PTS; ++j) {
          const float16 d = vload16(0, src[j] + o0);
#pragma unroll
          for (int c = 0; c < C_IN; ++c) acc[j][c] = fma(d, w[c], acc[j][c]);
        }
      }
    }
  }
#pragma unroll
  for (int j = 0; j < PTS; ++j) {
    const int ix = r + S * (m0 + j);
    if (ix >= W) continue;
    __global float* dst = d_in + ((size_t)row * W + ix) * IN_CS;
#pragma unroll
    for (int c = 0; c < C_IN; ++c) dst[c] = conv_hsum16(acc[j][c]);
  }
}
#endif
