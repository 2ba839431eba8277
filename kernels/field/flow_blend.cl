// LiDAR4D's flow-blended dynamic features (method.md §2; runtime/field/lidar4d_encoder.hpp):
// the dynamic block of the encoding (columns [col, col + width) of a row of `stride`) becomes
//   w0 · f(x, t) + w1 · f(x + flow_fwd, t + dt) + w2 · f(x + flow_bwd, t − dt),
// (0.5, 0.25, 0.25) inside the sequence; a missing neighbour (first / last frame) gives its
// weight to f(x, t), as LiDAR4D reuses the point's own features there. The small steps around
// it: per-point time fill, neighbour positions, the backward split of d_enc and the packing of
// the flow gradient. Host references: tests/field/test_lidar4d_encoder.cpp.

// out[offset + i] = value, i < n (a per-point time; zeroing a gradient slice).
__kernel void field_flow_fill(const int n, const float value, const uint offset,
                              __global float* out) {
  const int i = get_global_id(0);
  if (i < n) out[offset + i] = value;
}

// out[i] = x[i] + flow[i, col .. col + 3) (flow N × 6).
__kernel void field_flow_offset(const int n, const int col, __global const float* x,
                                __global const float* flow, __global float* out) {
  const int i = get_global_id(0);
  if (i >= n) return;
  for (int k = 0; k < 3; ++k) out[i * 3 + k] = x[i * 3 + k] + flow[i * 6 + col + k];
}

// enc[i·stride + col + c] = w0·enc[…] + w1·a[i·width + c] + w2·b[i·width + c]; a (b) is not
// read when w1 (w2) is 0, so a missing neighbour's buffer may hold anything.
__kernel void field_flow_blend_fwd(const int n, const int stride, const int col, const int width,
                                   const float w0, const float w1, const float w2,
                                   __global float* enc, __global const float* a,
                                   __global const float* b) {
  const int i = get_global_id(0);
  if (i >= n) return;
  __global float* e = enc + (size_t)i * stride + col;
  __global const float* ra = a + (size_t)i * width;
  __global const float* rb = b + (size_t)i * width;
  for (int c = 0; c < width; ++c) {
    float v = w0 * e[c];
    if (w1 != 0.0f) v += w1 * ra[c];
    if (w2 != 0.0f) v += w2 * rb[c];
    e[c] = v;
  }
}

// The dynamic block's gradient split three ways: d_own = w0·d, d_a = w1·d, d_b = w2·d
// (each N × width).
__kernel void field_flow_blend_bwd(const int n, const int stride, const int col, const int width,
                                   const float w0, const float w1, const float w2,
                                   __global const float* d_enc, __global float* d_own,
                                   __global float* d_a, __global float* d_b) {
  const int i = get_global_id(0);
  if (i >= n) return;
  __global const float* d = d_enc + (size_t)i * stride + col;
  for (int c = 0; c < width; ++c) {
    const size_t k = (size_t)i * width + c;
    d_own[k] = w0 * d[c];
    d_a[k] = w1 * d[c];
    d_b[k] = w2 * d[c];
  }
}

// out[i·width + c] = in[i·stride + col + c] (a block of columns to a dense N × width), and the
// reverse scatter; the other columns of the strided buffer are untouched.
__kernel void field_flow_cols_get(const int n, const int stride, const int col, const int width,
                                  __global const float* in, __global float* out) {
  const int i = get_global_id(0);
  if (i >= n) return;
  for (int c = 0; c < width; ++c) out[(size_t)i * width + c] = in[(size_t)i * stride + col + c];
}
__kernel void field_flow_cols_set(const int n, const int stride, const int col, const int width,
                                  __global const float* in, __global float* out) {
  const int i = get_global_id(0);
  if (i >= n) return;
  for (int c = 0; c < width; ++c) out[(size_t)i * stride + col + c] = in[(size_t)i * width + c];
}

// d_flow[i] = (has_a ? d_xa[i] : 0, has_b ? d_xb[i] : 0) (N × 6): a neighbour position
// x + flow moves with its flow exactly as with x.
__kernel void field_flow_pack_grad(const int n, const int has_a, const int has_b,
                                   __global const float* d_xa, __global const float* d_xb,
                                   __global float* d_flow) {
  const int i = get_global_id(0);
  if (i >= n) return;
  for (int k = 0; k < 3; ++k) {
    d_flow[i * 6 + k] = has_a ? d_xa[i * 3 + k] : 0.0f;
    d_flow[i * 6 + 3 + k] = has_b ? d_xb[i * 3 + k] : 0.0f;
  }
}
