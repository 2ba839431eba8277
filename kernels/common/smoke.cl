// Smoke kernels for the runtime's own tests and `sgnlf devices --smoke`: a saxpy and a
// Philox fill that must agree with the host generator word for word.
#include "common/philox.clh"

__kernel void common_saxpy_fwd(const int n, const float a, __global const float* x,
                               __global float* y) {
  const int i = get_global_id(0);
  if (i < n) y[i] = a * x[i] + y[i];
}

__kernel void common_philox_fill(const uint seed_lo, const uint seed_hi, const uint stream,
                                 const int n_blocks, __global uint4* out) {
  const int i = get_global_id(0);
  if (i < n_blocks) out[i] = philox_block(seed_lo, seed_hi, stream, (ulong)i);
}
