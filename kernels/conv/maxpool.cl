// 2×2 max pooling, stride 2, NHWC with channel strides (the U-Net's down stages of LiDAR4D's
// ray-drop refinement, method.md §2). HO = H / 2, WO = W / 2 (floor, as PyTorch's MaxPool2d(2):
// an odd last row or column is dropped and receives zero gradient). The window's maximum is the
// first one in the order (0,0), (0,1), (1,0), (1,1) (strict >), and the backward recomputes it
// from the forward input, so no index buffer and no atomics. Memory-bound: work-item = one
// (pixel, channel) of the output (forward) or input (backward), channels fastest (flat index
// p·C + c), so neighbouring work-items touch neighbouring floats.

// Position (0..3) of the first maximum of the window whose top-left element is `a`.
inline int conv_maxpool2_arg(__global const float* a, const int cs, const int row) {
  int k = 0;
  float m = a[0];
  if (a[cs] > m) { m = a[cs]; k = 1; }
  if (a[row] > m) { m = a[row]; k = 2; }
  if (a[row + cs] > m) k = 3;
  return k;
}

__kernel void conv_maxpool2_fwd(const int n_img, const int H, const int W, const int C,
                                const int in_cs, const int out_cs, __global const float* in,
                                __global float* out) {
  const int HO = H / 2, WO = W / 2;
  const int i = get_global_id(0);
  if (i >= n_img * HO * WO * C) return;
  const int p = i / C, c = i - p * C;  // p = (n·HO + oy)·WO + ox
  const int ox = p % WO, r = p / WO;
  const int oy = r % HO, n = r / HO;
  __global const float* a = in + ((size_t)(n * H + 2 * oy) * W + 2 * ox) * in_cs + c;
  const int row = W * in_cs;
  const float m = fmax(fmax(a[0], a[in_cs]), fmax(a[row], a[row + in_cs]));
  out[(size_t)p * out_cs + c] = m;
}

// d_in[n, y, x, c] (=|+=) d_out[n, y/2, x/2, c] where (y, x) is its window's first maximum,
// else (=|+=) 0.
__kernel void conv_maxpool2_bwd(const int n_img, const int H, const int W, const int C,
                                const int in_cs, const int out_cs, const int accumulate,
                                __global const float* in, __global const float* d_out,
                                __global float* d_in) {
  const int HO = H / 2, WO = W / 2;
  const int i = get_global_id(0);
  if (i >= n_img * H * W * C) return;
  const int p = i / C, c = i - p * C;  // p = (n·H + y)·W + x
  const int x = p % W, r = p / W;
  const int y = r % H, n = r / H;
  float g = 0.0f;
  if (y / 2 < HO && x / 2 < WO) {
    const int oy = y / 2, ox = x / 2;
    __global const float* a = in + ((size_t)(n * H + 2 * oy) * W + 2 * ox) * in_cs + c;
    const int k = conv_maxpool2_arg(a, in_cs, W * in_cs);
    if (k == (y & 1) * 2 + (x & 1)) g = d_out[((size_t)(n * HO + oy) * WO + ox) * out_cs + c];
  }
  __global float* dst = d_in + (size_t)p * in_cs + c;
  *dst = accumulate ? *dst + g : g;
}
