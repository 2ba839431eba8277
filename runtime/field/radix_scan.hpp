// The in-place exclusive scan of the radix sort's digit histograms (field::EntryReduction;
// kernels/field/radix_scan.cl): `units` rows of `count` words, each row scanned on its own.
// With min_work_items 0 (the cpu profile's radix_min_work_items) a row is one work-group of 64
// (entry_radix_scan), as always; above 0 a row whose one work-group would leave the launch under
// min_work_items work-items is split into blocks (reduce-then-scan: block sums, a scan of each
// row's block sums, the blocks scanned from their offsets), enough blocks that units · blocks ·
// 64 ≥ min_work_items where the row has the words (at least 64 a block). Integer sums: the same
// words either way, equal to a serial scan.
#pragma once
#include <cstddef>
#include <cstdint>

#include "cl/runtime.hpp"

namespace sgnlf::field {

class RadixScan {
 public:
  RadixScan(cl::Runtime& rt, size_t min_work_items);

  // Blocks a row of `count` words is scanned in (1: one work-group per row).
  uint32_t blocks(uint32_t units, uint32_t count) const;
  // Scans hist's first units · count words. Enqueued, no wait. Throws when hist is smaller.
  void scan(cl::Buffer& hist, uint32_t units, uint32_t count);

  static constexpr size_t kWorkGroup = 64;  // = SCAN_WG

 private:
  cl::Runtime& rt_;
  size_t min_work_items_;
  cl::Kernel row_k_, sums_k_, block_k_;
  cl::Buffer sums_;  // units · blocks words, grown on demand
};

}  // namespace sgnlf::field
