// 2×2 average pooling, stride 2, NHWC with channel strides (the multi-scale discriminator's
// input pyramid, method.md §4.3). HO = H / 2, WO = W / 2 (floor: an odd last row or column is
// dropped, and receives zero gradient). Work-item = one output (forward) or input (backward)
// pixel × channel; memory-bound, so no tiling.
__kernel void conv_avgpool2_fwd(const int n_img, const int H, const int W, const int C,
                                const int in_cs, const int out_cs, __global const float* in,
                                __global float* out) {
  const int HO = H / 2, WO = W / 2;
  const int p = get_global_id(0);  // (n·HO + oy)·WO + ox
  const int c = get_global_id(1);
  if (c >= C || p >= n_img * HO * WO) return;
  const int ox = p % WO, row = p / WO;
  const int oy = row % HO, n = row / HO;
  __global const float* a = in + ((size_t)(n * H + 2 * oy) * W + 2 * ox) * in_cs + c;
  __global const float* b = a + (size_t)W * in_cs;
  out[(size_t)p * out_cs + c] = 0.25f * ((a[0] + a[in_cs]) + (b[0] + b[in_cs]));
}

// d_in[n, y, x, c] (=|+=) 0.25 · d_out[n, y/2, x/2, c] inside the pooled area, else (=|+=) 0.
__kernel void conv_avgpool2_bwd(const int n_img, const int H, const int W, const int C,
                                const int in_cs, const int out_cs, const int accumulate,
                                __global const float* d_out, __global float* d_in) {
  const int HO = H / 2, WO = W / 2;
  const int p = get_global_id(0);  // (n·H + y)·W + x
  const int c = get_global_id(1);
  if (c >= C || p >= n_img * H * W) return;
  const int x = p % W, row = p / W;
  const int y = row % H, n = row / H;
  const float g = (y / 2 < HO && x / 2 < WO)
                      ? 0.25f * d_out[((size_t)(n * HO + y / 2) * WO + x / 2) * out_cs + c]
                      : 0.0f;
  __global float* dst = d_in + (size_t)p * in_cs + c;
  *dst = accumulate ? *dst + g : g;
}
