// The exclusive scan of the encoders' radix-sort histograms (runtime/field/radix_scan.hpp,
// kernels/field/entry_reduce.cl's sort): `units` rows of `count` words, hist[u·count + i], each
// scanned in place on its own (a row is one unit's 16·tiles digit-major words, so a (digit,
// tile) word becomes the first output position of that tile's pairs of that digit).
//   - entry_radix_scan: one work-group per row (common/scan.clh), the cpu profile's form, and
//     the scan of the block sums below;
//   - entry_radix_block_sums, entry_radix_scan, entry_radix_block_scan: reduce-then-scan over
//     blocks of `per` words, one work-group per (block, row), so that a big histogram gets
//     many work-groups: each block's sum, an exclusive scan of each row's block sums, then each
//     block scanned from its sum's offset.
// Integer sums: any grouping gives the same words, equal to a serial scan bit for bit.
//
// Defines: SCAN_WG (work-group size, a power of two).
#ifndef SCAN_WG
#define SCAN_WG 64
#endif
#if (SCAN_WG & (SCAN_WG - 1)) != 0
#error "SCAN_WG must be a power of two"
#endif
#include "common/scan.clh"

// Row get_group_id(0) of `count` words, by one work-group.
__kernel void entry_radix_scan(const uint count, __global uint* hist) {
  __local uint part[SCAN_WG];
  group_exclusive_scan(count, hist + (size_t)get_group_id(0) * count, part);
}

// sums[u·blocks + b] = the sum of block b = words [b·per, min(count, (b+1)·per)) of row u, for
// work-group (b, u) of a (blocks·SCAN_WG, units) range. The work-items stride the block (reads
// of consecutive words side by side) and their sums meet in a local-memory tree.
__kernel void entry_radix_block_sums(const uint count, const uint per,
                                     __global const uint* hist, __global uint* sums) {
  __local uint part[SCAN_WG];
  const uint lid = get_local_id(0), b = get_group_id(0), u = get_group_id(1);
  const uint lo = min(count, b * per), hi = min(count, lo + per);
  __global const uint* h = hist + (size_t)u * count;
  uint s = 0u;
  for (uint j = lo + lid; j < hi; j += SCAN_WG) s += h[j];
  part[lid] = s;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint w = SCAN_WG / 2u; w > 0u; w >>= 1) {
    if (lid < w) part[lid] += part[lid + w];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0u) sums[(size_t)u * get_num_groups(0) + b] = part[0];
}

// Block b of row u scanned in place from offset sums[u·blocks + b] (the scanned block sums:
// the row's words before the block).
__kernel void entry_radix_block_scan(const uint count, const uint per, __global uint* hist,
                                     __global const uint* sums) {
  __local uint part[SCAN_WG];
  const uint b = get_group_id(0), u = get_group_id(1);
  const uint lo = min(count, b * per), hi = min(count, lo + per);
  group_exclusive_scan_from(hi - lo, hist + (size_t)u * count + lo, part,
                            sums[(size_t)u * get_num_groups(0) + b]);
}
