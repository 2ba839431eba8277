// Roofline probes (runtime/harness/roofline.hpp): peak FLOP/s from independent float16 FMA
// chains, and streaming bandwidth from copy and triad over float4 arrays. Explicit vector
// types because PoCL does not vectorise loops across work-items (performance.md).

#define ROOFLINE_STEP(x) x = fma(x, va, vb)

// Each work-item runs 8 independent chains of 16-lane FMAs for `iters` steps:
// 8 · 16 · 2 · iters flops. out[gid] = fixed-order sum of every lane (keeps the work alive).
__kernel void roofline_fma_peak(const int iters, const float a, const float b,
                                __global float* out) {
  const int gid = (int)get_global_id(0);
  const float16 lane = (float16)(0.f, 1.f, 2.f, 3.f, 4.f, 5.f, 6.f, 7.f, 8.f, 9.f, 10.f,
                                 11.f, 12.f, 13.f, 14.f, 15.f) * 0.0625f;
  const float base = (float)(gid & 1023) * (1.0f / 1024.0f);
  float16 x0 = lane + base, x1 = lane - base, x2 = lane * 0.5f + base, x3 = lane * 0.25f - base;
  float16 x4 = base - lane, x5 = lane + 2.0f * base, x6 = lane * 0.75f, x7 = lane + 0.5f;
  const float16 va = (float16)(a), vb = (float16)(b);
  for (int i = 0; i < iters; ++i) {
    ROOFLINE_STEP(x0); ROOFLINE_STEP(x1); ROOFLINE_STEP(x2); ROOFLINE_STEP(x3);
    ROOFLINE_STEP(x4); ROOFLINE_STEP(x5); ROOFLINE_STEP(x6); ROOFLINE_STEP(x7);
  }
  const float16 s = ((x0 + x1) + (x2 + x3)) + ((x4 + x5) + (x6 + x7));
  const float8 h8 = s.lo + s.hi;
  const float4 h4 = h8.lo + h8.hi;
  const float2 h2 = h4.lo + h4.hi;
  out[gid] = h2.x + h2.y;
}

// dst[i] = src[i]: 2 · 16 bytes per work-item.
__kernel void roofline_copy_stream(__global const float4* src, __global float4* dst) {
  const size_t i = get_global_id(0);
  dst[i] = src[i];
}

// a[i] = b[i] + s · c[i] (STREAM triad): 3 · 16 bytes and 8 flops per work-item.
__kernel void roofline_triad_stream(const float s, __global float4* a, __global const float4* b,
                                    __global const float4* c) {
  const size_t i = get_global_id(0);
  a[i] = fma((float4)(s), c[i], b[i]);
}

// Random float2 reads from a table of mask + 1 entries (a power of two, sized beyond the
// caches): each work-item sums `per_item` reads at hashed, independent positions. The rate of
// cache-missing 8-byte reads, the roof of the hash-grid kernels' fine levels.
__kernel void roofline_gather_random(const int per_item, const uint mask,
                                     __global const float2* table, __global float* out) {
  const uint i = get_global_id(0);
  float2 acc = (float2)(0.0f);
  for (int k = 0; k < per_item; ++k) {
    const uint h = (i * 2654435761u) ^ ((uint)k * 805459861u) ^ ((uint)k << 20);
    acc += table[h & mask];
  }
  out[i] = acc.x + acc.y;
}
