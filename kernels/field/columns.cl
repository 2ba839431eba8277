// Strided column gather/scatter between the density MLP's N x 16 output and plain N vectors:
// the MLP writes the σ logit h0 as column 0 of its output, the volume renderer reads/writes h0 as
// a plain N vector (launched by pipeline::LidarNerfModel). Host references:
// tests/field/test_columns.cpp.

// out[i] = in[i * stride + col], i < n.
__kernel void field_column_get(const int n, const int stride, const int col,
                             __global const float* in, __global float* out) {
  const int i = get_global_id(0);
  if (i >= n) return;
  out[i] = in[(size_t)i * stride + col];
}

// out[i * stride + col] = in[i], i < n; the other columns of out are left untouched.
__kernel void field_column_set(const int n, const int stride, const int col,
                             __global const float* in, __global float* out) {
  const int i = get_global_id(0);
  if (i >= n) return;
  out[(size_t)i * stride + col] = in[i];
}
