// Work-group shapes of the local-memory tiled GEMMs (device profile gemm = "local_tiles";
// kernels/common/gemm_tile.clh): the profile's gemm_* keys turned into a kernel's tile, its
// -D defines and launch sizes, and the check that a program's tiles fit the device. Used by
// conv::Conv2d (field::Mlp computes the same shapes in mlp_gemm.cpp).
#pragma once
#include <algorithm>
#include <array>
#include <string>

#include "cl/device_profile.hpp"
#include "cl/runtime.hpp"
#include "core/error.hpp"

namespace sgnlf::cl {

// One kernel's work-group: lc x lr work-items covering tr = lr · block_rows rows by tc columns.
struct GemmTile {
  int tc = 16, lc = 16, lr = 1, tr = 1;
  static size_t ceil_div(size_t a, size_t b) { return (a + b - 1) / b; }
  // Global size over `rows` x `cols` (dimension 0 along the columns).
  std::array<size_t, 2> global(size_t rows, size_t cols) const {
    return {ceil_div(cols, size_t(tc)) * size_t(lc), ceil_div(rows, size_t(tr)) * size_t(lr)};
  }
  size_t work_items(size_t rows, size_t cols) const {
    const auto g = global(rows, cols);
    return g[0] * g[1];
  }
};

// The tile of a GEMM `width` columns wide: tc = min(tile, width), lc = tc / block_cols, as many
// rows of work-items as gemm_work_group allows.
inline GemmTile gemm_tile(const DeviceProfile& p, int width, int tile, int block_rows,
                          int block_cols) {
  GemmTile t;
  t.tc = std::min(tile, width);
  t.lc = std::max(1, t.tc / block_cols);
  t.lr = std::max(1, p.gemm_work_group / t.lc);
  t.tr = t.lr * block_rows;
  return t;
}

inline std::string gemm_define(const char* k, int v) {
  return std::string(" -D") + k + "=" + std::to_string(v);
}

// Throws ConfigError (naming the profile and `what`) when `local_floats` of local memory or a
// work-group of `tiles` exceeds the device (32 KiB at most: OpenCL 1.2's minimum).
template <class... Tiles>
void check_gemm_fit(const Runtime& rt, const std::string& what, size_t local_floats,
                    const Tiles&... tiles) {
  const auto& dev = rt.device();
  const std::string& name = rt.device_profile().name;
  constexpr size_t kMaxLocalBytes = 32 * 1024;
  const size_t local_bytes =
      dev.local_mem_bytes > 0 ? std::min<size_t>(kMaxLocalBytes, size_t(dev.local_mem_bytes))
                              : kMaxLocalBytes;
  if (local_floats * sizeof(float) > local_bytes)
    throw ConfigError("device profile '" + name + "': " + what + "'s local_tiles need " +
                      std::to_string(local_floats * sizeof(float)) +
                      " bytes of local memory, more than " + std::to_string(local_bytes) +
                      ": lower gemm_work_group, gemm_block_rows or gemm_tile_k");
  for (const GemmTile* s : {&tiles...})
    if (dev.max_work_group_size > 0 && size_t(s->lc) * size_t(s->lr) > dev.max_work_group_size)
      throw ConfigError("device profile '" + name + "': " + what + "'s local_tiles take " +
                        std::to_string(s->lc * s->lr) + " work-items per work-group, the device " +
                        std::to_string(dev.max_work_group_size) + ": lower gemm_work_group");
}

}  // namespace sgnlf::cl
