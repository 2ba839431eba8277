// Roofline probes for the field benchmarks: peak float16-vector FMA throughput and streaming
// copy bandwidth of the device, measured in the same run as the kernels they put in scale.

// 8 independent float16 FMA chains per work-item, `iters` rounds: 256·iters FLOPs per item.
__kernel void field_probe_fma(const int iters, const float a, __global float* out) {
  const int i = get_global_id(0);
  float16 x0 = (float16)(i * 1e-7f), x1 = x0 + 1e-3f, x2 = x0 + 2e-3f, x3 = x0 + 3e-3f;
  float16 x4 = x0 + 4e-3f, x5 = x0 + 5e-3f, x6 = x0 + 6e-3f, x7 = x0 + 7e-3f;
  const float16 b = (float16)(1e-6f);
  for (int k = 0; k < iters; ++k) {
    x0 = fma(x0, a, b); x1 = fma(x1, a, b); x2 = fma(x2, a, b); x3 = fma(x3, a, b);
    x4 = fma(x4, a, b); x5 = fma(x5, a, b); x6 = fma(x6, a, b); x7 = fma(x7, a, b);
  }
  const float16 s = ((x0 + x1) + (x2 + x3)) + ((x4 + x5) + (x6 + x7));
  out[i] = s.s0 + s.s5 + s.sa + s.sf;
}

// dst = src as float4 (read + write bandwidth).
__kernel void field_probe_copy(const int n4, __global const float4* src, __global float4* dst) {
  const int i = get_global_id(0);
  if (i < n4) dst[i] = src[i];
}

// Random float2 gathers from a table of mask + 1 entries (a power of two, sized beyond the
// caches): each work-item sums `per_item` reads at hashed, independent positions. The device's
// rate of cache-missing 8-byte reads, the roof of the hash-grid kernels' fine levels.
__kernel void field_probe_gather(const int per_item, const uint mask,
                                 __global const float2* table, __global float* out) {
  const uint i = get_global_id(0);
  float2 acc = (float2)(0.0f);
  for (int k = 0; k < per_item; ++k) {
    const uint h = (i * 2654435761u) ^ ((uint)k * 805459861u) ^ ((uint)k << 20);
    acc += table[h & mask];
  }
  out[i] = acc.x + acc.y;
}
