// Bilinear ×2 upsampling with align_corners = true (PyTorch's nn.Upsample(scale_factor=2,
// mode='bilinear', align_corners=True), LiDAR4D's U-Net up stages, method.md §2), written
// zero-padded into a target of TH × TW >= 2H × 2W at offset ((TH − 2H) / 2, (TW − 2W) / 2)
// (LiDAR4D pads the upsampled map to the skip's size) and at channels [dst_off, dst_off + C) of
// a target with channel stride out_cs: the skip concatenation needs no extra copy of this half.
// Source coordinate of output row o: s = o · (H − 1) / (2H − 1) (0 when H = 1), taps floor(s)
// and floor(s) + 1 (clamped), weights 1 − frac and frac, in float as PyTorch computes them.
// Work-item = one (pixel, channel) of the target (forward) or input (backward), channels fastest
// (flat index p·C + c); memory-bound.

// Scale (in − 1) / (out − 1) in float, 0 for out <= 1.
inline float conv_up_scale(const int in, const int out) {
  return out > 1 ? (float)(in - 1) / (float)(out - 1) : 0.0f;
}

// Taps i0, i1 and weights l0, l1 of output index o.
inline void conv_up_taps(const int o, const float scale, const int in, int* i0, int* i1,
                         float* l0, float* l1) {
  const float s = scale * (float)o;
  const int a = (int)s;
  *i0 = a;
  *i1 = a + (a < in - 1 ? 1 : 0);
  *l1 = s - (float)a;
  *l0 = 1.0f - *l1;
}

__kernel void conv_upsample2_fwd(const int n_img, const int H, const int W, const int C,
                                 const int in_cs, const int TH, const int TW, const int out_cs,
                                 const int dst_off, __global const float* in,
                                 __global float* out) {
  const int i = get_global_id(0);
  if (i >= n_img * TH * TW * C) return;
  const int p = i / C, c = i - p * C;  // p = (n·TH + ty)·TW + tx
  const int tx = p % TW, r = p / TW;
  const int ty = r % TH, n = r / TH;
  const int HO = 2 * H, WO = 2 * W;
  const int oy = ty - (TH - HO) / 2, ox = tx - (TW - WO) / 2;
  float v = 0.0f;
  if (oy >= 0 && oy < HO && ox >= 0 && ox < WO) {
    int y0, y1, x0, x1;
    float ly0, ly1, lx0, lx1;
    conv_up_taps(oy, conv_up_scale(H, HO), H, &y0, &y1, &ly0, &ly1);
    conv_up_taps(ox, conv_up_scale(W, WO), W, &x0, &x1, &lx0, &lx1);
    __global const float* img = in + (size_t)n * H * W * in_cs + c;
    const float a = img[((size_t)y0 * W + x0) * in_cs], b = img[((size_t)y0 * W + x1) * in_cs];
    const float d = img[((size_t)y1 * W + x0) * in_cs], e = img[((size_t)y1 * W + x1) * in_cs];
    v = ly0 * (lx0 * a + lx1 * b) + ly1 * (lx0 * d + lx1 * e);
  }
  out[(size_t)p * out_cs + dst_off + c] = v;
}

// Weight of input index i in output index o (both taps may be i at the last index).
inline float conv_up_weight(const int o, const float scale, const int in, const int i) {
  int i0, i1;
  float l0, l1;
  conv_up_taps(o, scale, in, &i0, &i1, &l0, &l1);
  return (i0 == i ? l0 : 0.0f) + (i1 == i ? l1 : 0.0f);
}

#define CONV_UP_RANGE 16

// Output indices that may read input index i: s = o · scale within (i − 1, i + 1), widened by
// one on each side against rounding (their weights are computed exactly, zeros skipped).
inline void conv_up_range(const int i, const float scale, const int out, int* lo, int* hi) {
  if (scale == 0.0f) {
    *lo = 0;
    *hi = out - 1;
    return;
  }
  *lo = max(0, (int)floor((float)(i - 1) / scale) - 1);
  *hi = min(out - 1, (int)ceil((float)(i + 1) / scale) + 1);
}

// d_in[n, y, x, c] (=|+=) Σ over output pixels (row-major order) of weight · d_out, read from
// channel dst_off + c of the padded target's gradient (the transpose of the forward).
__kernel void conv_upsample2_bwd(const int n_img, const int H, const int W, const int C,
                                 const int in_cs, const int TH, const int TW, const int out_cs,
                                 const int dst_off, const int accumulate,
                                 __global const float* d_out, __global float* d_in) {
  const int i = get_global_id(0);
  if (i >= n_img * H * W * C) return;
  const int p = i / C, c = i - p * C;  // p = (n·H + y)·W + x
  const int x = p % W, r = p / W;
  const int y = r % H, n = r / H;
  const int HO = 2 * H, WO = 2 * W, py = (TH - HO) / 2, px = (TW - WO) / 2;
  const float sy = conv_up_scale(H, HO), sx = conv_up_scale(W, WO);
  int oy0, oy1, ox0, ox1;
  conv_up_range(y, sy, HO, &oy0, &oy1);
  conv_up_range(x, sx, WO, &ox0, &ox1);
  __global const float* g = d_out + (size_t)n * TH * TW * out_cs + dst_off + c;
  // The column weights once: the range has at most 2 / scale + 5 <= 11 entries (scale >= 1/3
  // for W >= 2; 2 entries for W = 1), within CONV_UP_RANGE with room for rounding.
  float wxs[CONV_UP_RANGE];
  for (int k = 0; k < CONV_UP_RANGE; ++k)
    wxs[k] = ox0 + k <= ox1 ? conv_up_weight(ox0 + k, sx, W, x) : 0.0f;
  float acc = 0.0f;
  for (int oy = oy0; oy <= oy1; ++oy) {
    const float wy = conv_up_weight(oy, sy, H, y);
    if (wy == 0.0f) continue;
    __global const float* grow = g + ((size_t)(oy + py) * TW + ox0 + px) * out_cs;
    float row = 0.0f;
    for (int k = 0; k <= ox1 - ox0; ++k)
      if (wxs[k] != 0.0f) row += wxs[k] * grow[(size_t)k * out_cs];
    acc += wy * row;
  }
  __global float* dst = d_in + (size_t)p * in_cs + c;
  *dst = accumulate ? *dst + acc : acc;
}
