// EntryReduction (entry_reduction.hpp): the ranges table, pair buffers and the enqueueing of
// the sort and reduction kernels of kernels/field/entry_reduce.cl.
#include "field/entry_reduction.hpp"

#include <algorithm>
#include <string>

#include "cl/launch.hpp"
#include "core/error.hpp"

namespace sgnlf::field {
namespace {
constexpr uint32_t kRadixBits = 4;
}  // namespace

EntryReduction::EntryReduction(cl::Runtime& rt, int features, int units, int pairs_per_point,
                               int pairs_per_vector, std::vector<EntryRange> ranges)
    : rt_(rt), features_(features), units_(units), pairs_(pairs_per_point),
      per_vector_(pairs_per_vector), tile_(uint32_t(rt.device_profile().radix_tile)),
      min_work_items_(size_t(rt.device_profile().radix_min_work_items)),
      scan_(rt, min_work_items_) {
  if (units < 1 || pairs_per_point < 1 || pairs_per_vector < 1 ||
      pairs_per_point % pairs_per_vector != 0)
    throw Error("EntryReduction: " + std::to_string(units) + " units, " +
                std::to_string(pairs_per_point) + " pairs per point in vectors of " +
                std::to_string(pairs_per_vector) + " (must divide it)");
  if (ranges.empty()) throw Error("EntryReduction: no entry ranges");
  std::vector<uint32_t> table;
  std::vector<std::pair<uint64_t, uint64_t>> spans;
  uint64_t top = 0;
  for (const auto& r : ranges) {
    if (r.unit >= uint32_t(units))
      throw Error("EntryReduction: range of unit " + std::to_string(r.unit) + " with " +
                  std::to_string(units) + " units");
    if (r.count == 0) continue;
    table.insert(table.end(), {r.unit, r.first, r.count, uint32_t(entries_)});
    spans.emplace_back(r.first, uint64_t(r.first) + r.count);
    entries_ += r.count;
    top = std::max(top, uint64_t(r.first) + r.count);
  }
  std::sort(spans.begin(), spans.end());
  for (size_t i = 1; i < spans.size(); ++i)
    if (spans[i].first < spans[i - 1].second)
      throw Error("EntryReduction: entry ranges overlap at entry " +
                  std::to_string(spans[i].first));
  if (top >= (uint64_t(1) << 32) - 1 || entries_ >= (uint64_t(1) << 32))
    throw Error("EntryReduction: " + std::to_string(top) + " entries exceed 32-bit keys");
  n_ranges_ = uint32_t(table.size() / 4);
  ranges_ = cl::Buffer::from(rt_, table);
  int bits = 0;
  while (bits < 32 && (uint64_t(1) << bits) < top) ++bits;  // keys < top ≤ 2^bits
  passes_ = (bits + int(kRadixBits) - 1) / int(kRadixBits);
  const std::string opt = "-DFEATURES=" + std::to_string(features) +
                          " -DRADIX_TILE=" + std::to_string(tile_);
  const std::string file = "field/entry_reduce.cl";
  tile_kernels(tile_);
  reduce_k_ = rt_.kernel(file, "entry_reduce", opt);
  zero_k_ = rt_.kernel(file, "entry_zero", opt);
}

EntryReduction::TileKernels& EntryReduction::tile_kernels(uint32_t tile) {
  auto it = by_tile_.find(tile);
  if (it != by_tile_.end()) return it->second;
  const std::string opt = "-DFEATURES=" + std::to_string(features_) +
                          " -DRADIX_TILE=" + std::to_string(tile);
  const std::string file = "field/entry_reduce.cl";
  return by_tile_[tile] = {rt_.kernel(file, "entry_radix_hist", opt),
                           rt_.kernel(file, "entry_radix_scatter", opt)};
}

uint32_t EntryReduction::tile_for(uint64_t m) const {
  uint32_t tile = tile_;
  while (tile > 1 && (m + tile - 1) / tile * uint64_t(units_) < min_work_items_) tile /= 2;
  return tile;
}

void EntryReduction::reserve(int n) {
  if (n < 0) throw Error("EntryReduction: negative point count " + std::to_string(n));
  if (size_t(n) <= points_) return;
  const uint64_t m = uint64_t(n) * uint64_t(pairs_);
  if (m >= (uint64_t(1) << 32))
    throw Error("EntryReduction: " + std::to_string(n) + " points × " + std::to_string(pairs_) +
                " pairs exceed 32-bit pair indices");
  const size_t total = size_t(m) * size_t(units_);
  // The most tiles a sort of up to m pairs a unit makes: ⌈m / radix_tile⌉ at the full tile;
  // a halved tile (tile_for) had under min_work_items_ / units tiles at twice its size, so it
  // has at most 2 min_work_items_ / units + 1.
  const size_t tiles =
      std::max((size_t(m) + tile_ - 1) / tile_, 2 * min_work_items_ / size_t(units_) + 1);
  for (int b = 0; b < 2; ++b) {
    keys_[b] = cl::Buffer(rt_, total * sizeof(uint32_t));
    vals_[b] = cl::Buffer(rt_, total * sizeof(uint32_t));
  }
  coef_ = cl::Buffer(rt_, total * sizeof(float));
  vec_ = cl::Buffer(rt_, total / size_t(per_vector_) * size_t(features_) * sizeof(float));
  hist_ = cl::Buffer(rt_, size_t(units_) * 16 * tiles * sizeof(uint32_t));
  points_ = size_t(n);
}

void EntryReduction::reduce(int n, cl::Buffer& grad, size_t grad_offset, bool accumulate) {
  if (size_t(n) > points_)
    throw Error("EntryReduction::reduce: " + std::to_string(n) + " points, buffers for " +
                std::to_string(points_) + " (reserve first)");
  const uint32_t m = uint32_t(size_t(n) * size_t(pairs_));
  const uint32_t tile = tile_for(m);
  const uint32_t tiles = (m + tile - 1) / tile;
  TileKernels& tk = tile_kernels(tile);
  if (!accumulate) zero(grad, grad_offset);
  if (m == 0) return;
  int cur = 0;
  for (int p = 0; p < passes_; ++p) {
    const uint32_t shift = uint32_t(p) * kRadixBits;
    // The trace's element counts: the pairs sorted (keys_ is sized for reserve()'s points,
    // which may be more; RadixScan gives the histogram words it scans).
    const size_t pairs = size_t(m) * size_t(units_);
    tk.hist.set_args(m, tiles, shift, keys_[cur], hist_);
    cl::launch_rows(tk.hist, tiles, size_t(units_), pairs);
    scan_.scan(hist_, uint32_t(units_), 16 * tiles);
    tk.scatter.set_args(m, tiles, shift, keys_[cur], vals_[cur], hist_, keys_[1 - cur],
                        vals_[1 - cur]);
    cl::launch_rows(tk.scatter, tiles, size_t(units_), pairs);
    cur = 1 - cur;
  }
  reduce_k_.set_args(m, uint32_t(per_vector_), keys_[cur], vals_[cur], coef_, vec_, grad,
                     uint32_t(grad_offset), accumulate ? 1 : 0);
  cl::launch_rows(reduce_k_, m, size_t(units_));
}

void EntryReduction::zero(cl::Buffer& grad, size_t grad_offset) {
  zero_k_.set_args(uint32_t(entries_), n_ranges_, ranges_, grad, uint32_t(grad_offset));
  // The trace's element count: the ranges' floats, not the flat gradient they lie in.
  cl::launch_1d(zero_k_, entries_, entries_ * size_t(features_));
}

}  // namespace sgnlf::field
