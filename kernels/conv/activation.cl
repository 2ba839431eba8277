// Leaky ReLU, elementwise over a flat float buffer (method.md §4.3: slope 0.2 in the
// discriminator): y = x for x > 0, else slope · x. Work-item = 16 consecutive floats
// (vload16/vstore16), the tail of a count that is not a multiple of 16 element by element.
__kernel void conv_leaky_relu_fwd(const int n, const float slope, __global const float* x,
                                  __global float* y) {
  const int i0 = get_global_id(0) * 16;
  if (i0 >= n) return;
  if (i0 + 16 <= n) {
    const float16 v = vload16(0, x + i0);
    vstore16(select(v * slope, v, v > (float16)(0.0f)), 0, y + i0);
  } else {
    for (int i = i0; i < n; ++i) y[i] = x[i] > 0.0f ? x[i] : slope * x[i];
  }
}

// Backward from the forward input x: dx = dy for x > 0, else slope · dy.
__kernel void conv_leaky_relu_bwd(const int n, const float slope, __global const float* x,
                                  __global const float* dy, __global float* dx) {
  const int i0 = get_global_id(0) * 16;
  if (i0 >= n) return;
  if (i0 + 16 <= n) {
    const float16 v = vload16(0, x + i0);
    const float16 g = vload16(0, dy + i0);
    vstore16(select(g * slope, g, v > (float16)(0.0f)), 0, dx + i0);
  } else {
    for (int i = i0; i < n; ++i) dx[i] = x[i] > 0.0f ? dy[i] : slope * dy[i];
  }
}
