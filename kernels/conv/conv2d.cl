// 2-D convolution, NHWC, as register-tiled implicit GEMMs (performance.md: float16 vector
// accumulators, weight rows loaded once per tile and reused over PTS pixels from registers).
// Used by the PatchGAN discriminator (method.md §4.3) and meant for LiDAR4D's ray-drop U-Net.
//
// Tensors are NHWC with a channel stride: element (n, y, x, c) at ((n·H + y)·W + x)·CS + c.
// The input has IN_CS >= C_IN; the output has O_PAD = round_up(C_OUT, 16) (padding channels 0).
// Parameters at w_off: W[(ky·K + kx)·C_IN + c][O_PAD] then bias[O_PAD], i.e. the MLP's layout
// (kernels/field/mlp.cl) with one weight row per (tap, input channel); padding columns are 0.
// Out-of-image taps read a row of zeros (`zeros`, >= max(C_IN, C_OUT) floats): zero padding
// without branches in the inner loops.
// Defines (runtime/conv/conv2d.cpp): C_IN, IN_CS, IN_PAD = round_up(C_IN, 16), C_OUT, O_PAD,
// K (kernel size), S (stride), P (zero padding), PTS (pixels per work-item), ROWS (weight rows
// per work-item in the weight gradient).
#define TAPS (K * K)
#define N_ROWS (TAPS * C_IN)

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
#pragma unroll
      for (int j = 0; j < PTS; ++j) {
        const int ix = (ox0 + j) * S - P + kx;
        const int ok = row_ok && ix >= 0 && ix < W && ox0 + j < WO;
        src[j] = ok ? in_row + (size_t)ix * IN_CS : zeros;
      }
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

// Narrow outputs (C_OUT <= 2, e.g. the PatchGAN's logit layer or a U-Net's 1-channel head): the
// wide kernels would compute 16 padded output lanes for one useful one, so these vectorise over
// 16 input channels instead (C_IN and IN_CS multiples of 16). Same layouts and results.
#if C_OUT <= 2 && C_IN % 16 == 0 && IN_CS % 16 == 0
#define NARROW 1
inline float hsum16(const float16 v) {
  const float8 a = v.lo + v.hi;
  const float4 b = a.lo + a.hi;
  const float2 c = b.lo + b.hi;
  return c.x + c.y;
}

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
#pragma unroll
      for (int j = 0; j < PTS; ++j) {
        const int ix = (ox0 + j) * S - P + kx;
        const int ok = row_ok && ix >= 0 && ix < W && ox0 + j < WO;
        src[j] = ok ? in_row + (size_t)ix * IN_CS : zeros;
      }
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
        if (q == o) v = bias[o] + hsum16(acc[j][q]);
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
#else
#define NARROW 0
#endif

// Input backward for narrow inputs (C_IN <= 4, e.g. the 2-channel [D_ij, D_j] pair): the wide
// kernel would fill 16 lanes of input channels for 2 useful ones, so this one vectorises over
// output channels, d_in[c] = Σ_tap hsum(d_out[p'][o-block] · W[tap][c][o-block]), straight from
// the parameter layout (no transpose). Work-item = PTS input pixels (same residue, as in
// conv2d_bwd_in) × all C_IN channels; dim 0 as conv2d_bwd_in, no channel-block dimension.
#if C_IN <= 4
#ifndef NARROW_HSUM
#define NARROW_HSUM
inline float hsum16_in(const float16 v) {
  const float8 a = v.lo + v.hi;
  const float4 b = a.lo + a.hi;
  const float2 c = b.lo + b.hi;
  return c.x + c.y;
}
#endif
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
    for (int c = 0; c < C_IN; ++c) dst[c] = hsum16_in(acc[j][c]);
  }
}
#endif
