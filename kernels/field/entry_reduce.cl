// The deterministic parallel parameter backward of the encoders (hash grid, time hash grid,
// K-Planes; runtime/field/entry_reduction.hpp): the encoder's pair kernel writes, per work unit
// u (a level, or a K-Planes scale-group) and point i, P contributions j = i·P + c: the entry
// they add to (key), a scalar coefficient and, shared by PV consecutive pairs, a feature
// vector; the gradient of an entry is Σ coef · vec over its pairs in pair order, which is the
// serial kernels' order (point by point, corner by corner). These kernels sort each unit's
// pairs by key with a stable LSD radix sort (4-bit digits; per pass a histogram per tile of
// RADIX_TILE pairs, an exclusive scan per unit (kernels/field/radix_scan.cl), a scatter that
// walks each tile in order); then the first pair of each entry's run sums the run in the sorted
// (= pair) order with the serial kernels' fma, after entry_zero cleared the units' entries
// (unless accumulating). No float atomics: the result is bit-identical to the serial kernels'.
//
// Layouts: keys/vals/coef[u·m + j] (m = n·P pairs per unit; vals start as j), vec[(u·m + j)/PV]
// (FEATURES floats each), hist[(u·16 + digit)·tiles + tile]. ranges[r] = (unit, first entry,
// entries, first work-item): the entries unit r.x owns (entry_zero's work-items).
//
// Defines: FEATURES (1, 2, 4, 8), RADIX_TILE (pairs per work-item of hist and scatter).
#ifndef FEATURES
#error "FEATURES must be defined"
#endif
#ifndef RADIX_TILE
#define RADIX_TILE 256
#endif
#define HALF_TABLE 0
#include "field/hashgrid.clh"

#define RADIX 16

// hist[(u·16 + d)·tiles + g] = pairs of tile g of unit u whose key has digit d at `shift`.
__kernel void entry_radix_hist(const uint m, const uint tiles, const uint shift,
                               __global const uint* keys, __global uint* hist) {
  const uint g = get_global_id(0), u = get_global_id(1);
  if (g >= tiles) return;
  uint c[RADIX];
  for (int d = 0; d < RADIX; ++d) c[d] = 0u;
  __global const uint* k = keys + (size_t)u * m;
  const uint end = min(m, (g + 1u) * RADIX_TILE);
  for (uint j = g * RADIX_TILE; j < end; ++j) ++c[(k[j] >> shift) & (RADIX - 1)];
  for (int d = 0; d < RADIX; ++d) hist[((size_t)u * RADIX + d) * tiles + g] = c[d];
}

// Stable scatter of one pass: tile g of unit u walks its pairs in order and moves each to the
// next position of its digit (from the scanned histogram).
__kernel void entry_radix_scatter(const uint m, const uint tiles, const uint shift,
                                  __global const uint* keys_in, __global const uint* vals_in,
                                  __global const uint* hist, __global uint* keys_out,
                                  __global uint* vals_out) {
  const uint g = get_global_id(0), u = get_global_id(1);
  if (g >= tiles) return;
  uint o[RADIX];
  for (int d = 0; d < RADIX; ++d) o[d] = hist[((size_t)u * RADIX + d) * tiles + g];
  const size_t base = (size_t)u * m;
  const uint end = min(m, (g + 1u) * RADIX_TILE);
  for (uint j = g * RADIX_TILE; j < end; ++j) {
    const uint key = keys_in[base + j];
    const uint dst = o[(key >> shift) & (RADIX - 1)]++;
    keys_out[base + dst] = key;
    vals_out[base + dst] = vals_in[base + j];
  }
}

// The range of work-item w and the entry it owns.
inline uint4 er_range(uint w, uint n_ranges, __global const uint4* ranges) {
  uint lo = 0u, hi = n_ranges;
  while (hi - lo > 1u) {
    const uint mid = (lo + hi) / 2u;
    if (ranges[mid].w <= w) lo = mid;
    else hi = mid;
  }
  return ranges[lo];
}

// One work-item per sorted pair position j of unit u; the first pair of each entry's run sums
// the run in order: grad[entry] = (accumulate ? grad[entry] : 0) + Σ coef · vec, each term one
// fma. Entries no pair names are left alone (entry_zero clears them first unless accumulating).
__kernel void entry_reduce(const uint m, const uint pv, __global const uint* keys,
                           __global const uint* vals, __global const float* coef,
                           __global const float* vec, __global float* grad,
                           const uint grad_offset, const int accumulate) {
  const uint j = get_global_id(0), u = get_global_id(1);
  if (j >= m) return;
  const size_t base = (size_t)u * m;
  __global const uint* k = keys + base;
  const uint key = k[j];
  if (j > 0u && k[j - 1u] == key) return;
  __global float* out = grad + grad_offset + (size_t)key * FEATURES;
  featv acc = accumulate ? LOADF(out) : (featv)(0.0f);
  for (uint r = j; r < m && k[r] == key; ++r) {
    const size_t pair = base + vals[base + r];
    acc = fma((featv)(coef[pair]), LOADF(vec + (pair / pv) * FEATURES), acc);
  }
  STOREF(acc, out);
}

// Zeroes every entry of every range (the atomic backward's start).
__kernel void entry_zero(const uint items, const uint n_ranges, __global const uint4* ranges,
                         __global float* grad, const uint grad_offset) {
  const uint w = get_global_id(0);
  if (w >= items) return;
  const uint4 r = er_range(w, n_ranges, ranges);
  STOREF((featv)(0.0f), grad + grad_offset + (size_t)(r.y + (w - r.w)) * FEATURES);
}
