// The deterministic parallel parameter backward shared by the encoders (hash grid, time hash
// grid, K-Planes; kernels/field/entry_reduce.cl). An encoder's pair kernel writes, per work
// unit u (a level, a scale-group) and point i, P contributions j = i·P + c into keys() (the
// entry, an index into the module's gradient slice in entries of F floats), vals() (j),
// coef() (a scalar) and, once per PV consecutive pairs, vec() (F floats). reduce() then sorts
// each unit's pairs by entry (stable radix sort, ⌈bits/4⌉ passes of histogram, scan and
// scatter) and writes each entry the fma-sum of coef · vec over its pairs in pair order (the
// first pair of each entry's run sums the run): the serial kernels' summation order, so the
// result is bit-identical to them, with one work-item per tile of pairs (the device profile's
// radix_tile, halved for small sorts down to radix_min_work_items work-items; the stable sort's
// order is the same at any tile; its histogram scanned in blocks of many work-groups under
// radix_min_work_items > 0, field::RadixScan) or per pair instead of one per unit.
//
// The ranges say which entries each unit owns, and every key a unit's pair kernel writes must
// be one of them: reduce() then writes every one of them (zero, or the old value when
// accumulating, where no pair names it) and nothing else.
#pragma once
#include <cstdint>
#include <map>
#include <vector>

#include "cl/runtime.hpp"
#include "field/radix_scan.hpp"

namespace sgnlf::field {

struct EntryRange {
  uint32_t unit = 0;   // the work unit owning the entries
  uint32_t first = 0;  // first entry (in entries of F floats from the module's gradient slice)
  uint32_t count = 0;  // entries
};

class EntryReduction {
 public:
  // Throws when P is not a multiple of PV, a range names a unit ≥ units, or the ranges overlap.
  EntryReduction(cl::Runtime& rt, int features, int units, int pairs_per_point,
                 int pairs_per_vector, std::vector<EntryRange> ranges);

  // Sizes the pair buffers for n points (grows only; reallocates, so set kernel arguments
  // after it). Throws when n·P pairs do not fit 32-bit indices.
  void reserve(int n);
  cl::Buffer& keys() { return keys_[0]; }
  cl::Buffer& vals() { return vals_[0]; }
  cl::Buffer& coef() { return coef_; }
  cl::Buffer& vec() { return vec_; }

  // Sorts the pairs of n points (reserve(n) and the pair kernel first) and writes every range's
  // entries of grad[grad_offset + entry·F + f]. Enqueued, no wait.
  void reduce(int n, cl::Buffer& grad, size_t grad_offset, bool accumulate);
  // Zeroes every range's entries (the atomic backward's start). Enqueued, no wait.
  void zero(cl::Buffer& grad, size_t grad_offset);

  // Radix passes per sort (4 bits each, enough for the largest entry index).
  int passes() const { return passes_; }
  size_t entries() const { return entries_; }

 private:
  cl::Runtime& rt_;
  int features_, units_, pairs_, per_vector_;
  // The device profile's radix_tile and radix_min_work_items when made: a sort of m pairs a
  // unit runs at tile_for(m) (RADIX_TILE), whose hist/scatter kernels are built on first use.
  uint32_t tile_;
  size_t min_work_items_;
  RadixScan scan_;  // the histogram scan (in blocks under radix_min_work_items > 0)
  struct TileKernels {
    cl::Kernel hist, scatter;
  };
  std::map<uint32_t, TileKernels> by_tile_;
  TileKernels& tile_kernels(uint32_t tile);
  uint32_t tile_for(uint64_t m) const;
  int passes_ = 0;
  size_t entries_ = 0;
  uint32_t n_ranges_ = 0;
  cl::Buffer ranges_;
  cl::Buffer keys_[2], vals_[2], coef_, vec_, hist_;
  size_t points_ = 0;
  cl::Kernel reduce_k_, zero_k_;
};

}  // namespace sgnlf::field
