// RadixScan (radix_scan.hpp): the choice of blocks and the launches of kernels/field/
// radix_scan.cl.
#include "field/radix_scan.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"

namespace sgnlf::field {

RadixScan::RadixScan(cl::Runtime& rt, size_t min_work_items)
    : rt_(rt), min_work_items_(min_work_items) {
  const std::string opt = "-DSCAN_WG=" + std::to_string(kWorkGroup);
  const std::string file = "field/radix_scan.cl";
  row_k_ = rt_.kernel(file, "entry_radix_scan", opt);
  if (min_work_items_ > 0) {
    sums_k_ = rt_.kernel(file, "entry_radix_block_sums", opt);
    block_k_ = rt_.kernel(file, "entry_radix_block_scan", opt);
  }
}

uint32_t RadixScan::blocks(uint32_t units, uint32_t count) const {
  if (min_work_items_ == 0 || units == 0) return 1;
  const uint64_t group_rows = uint64_t(units) * kWorkGroup;
  // Enough blocks for min_work_items, each of at least a work-group's words; then as many
  // blocks of that size as the row needs (the last may be short).
  uint64_t b = std::min<uint64_t>((min_work_items_ + group_rows - 1) / group_rows,
                                  uint64_t(count) / kWorkGroup);
  if (b <= 1) return 1;
  const uint64_t per = (uint64_t(count) + b - 1) / b;
  return uint32_t((uint64_t(count) + per - 1) / per);
}

void RadixScan::scan(cl::Buffer& hist, uint32_t units, uint32_t count) {
  const size_t words = size_t(units) * count;
  if (hist.bytes() < words * sizeof(uint32_t))
    throw Error("RadixScan: " + std::to_string(units) + " rows of " + std::to_string(count) +
                " words in a buffer of " + std::to_string(hist.bytes()) + " bytes");
  if (words == 0) return;
  const uint32_t b = blocks(units, count);
  if (b == 1) {
    row_k_.set_args(count, hist);
    row_k_.launch({kWorkGroup * units}, {kWorkGroup}, words);
    return;
  }
  const uint32_t per = (count + b - 1) / b;
  const size_t n_sums = size_t(units) * b;
  if (sums_.bytes() < n_sums * sizeof(uint32_t)) sums_ = cl::Buffer(rt_, n_sums * sizeof(uint32_t));
  sums_k_.set_args(count, per, hist, sums_);
  sums_k_.launch({kWorkGroup * b, units}, {kWorkGroup, 1}, words);
  row_k_.set_args(b, sums_);
  row_k_.launch({kWorkGroup * units}, {kWorkGroup}, n_sums);
  block_k_.set_args(count, per, hist, sums_);
  block_k_.launch({kWorkGroup * b, units}, {kWorkGroup, 1}, words);
}

}  // namespace sgnlf::field
