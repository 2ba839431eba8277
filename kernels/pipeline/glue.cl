// Glue between the field and render modules in a training step (pipeline module):
// strided column gather/scatter (the density MLP writes h0 as column 0 of its N x 16 output,
// the volume renderer reads/writes h0 as a plain N vector) and the clamp of sample positions
// to the normalised scene box [-bound, bound]^3 (LiDAR-NeRF/torch-ngp clamp xyzs to the aabb).
// Host references: tests/pipeline/test_glue.cpp.

// out[i] = in[i * stride + col], i < n.
__kernel void pipeline_column_get(const int n, const int stride, const int col,
                                  __global const float* in, __global float* out) {
  const int i = get_global_id(0);
  if (i >= n) return;
  out[i] = in[(size_t)i * stride + col];
}

// out[i * stride + col] = in[i], i < n; the other columns of out are left untouched.
__kernel void pipeline_column_set(const int n, const int stride, const int col,
                                  __global const float* in, __global float* out) {
  const int i = get_global_id(0);
  if (i >= n) return;
  out[(size_t)i * stride + col] = in[i];
}

// x[k] = clamp(x[k], -bound, bound) for k < n (n = 3 x points), in place.
__kernel void pipeline_clamp_fwd(const int n, const float bound, __global float* x) {
  const int k = get_global_id(0);
  if (k >= n) return;
  x[k] = clamp(x[k], -bound, bound);
}
