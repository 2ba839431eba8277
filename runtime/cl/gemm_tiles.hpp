// Work-group shapes of the local-memory tiled GEMMs (device profile gemm = "local_tiles";
// kernels/common/gemm_tile.clh): the profile's gemm_* keys turned into a kernel's tile, its
// -D defines and launch sizes, the check that a program's tiles fit the device, and a layer's
// three GEMM kernels (forward, input backward, weight gradient) in the profile's register block
// and in the 1 x 1 block of small launches. One copy for conv::Conv2d (kernels/conv/
// conv2d_tiles.cl) and field::Mlp (kernels/field/mlp_tiles.cl).
#pragma once
#include <algorithm>
#include <array>
#include <string>
#include <utility>

#include "cl/device_profile.hpp"
#include "cl/memory.hpp"
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

// Columns (padded to 16) of a layer's three GEMMs: the forward's outputs, the input
// backward's inputs and the weight gradient's outputs.
struct GemmWidths {
  int fwd = 16, bwd_in = 16, wgt = 16;
};

// The three GEMMs' tiles with one register block: the profile's, or (small) a 1 x 1 block
// with 16-column tiles. Every sum keeps its order whatever the block (gemm_tile.clh).
struct GemmShapes {
  int block_rows = 1, block_cols = 1;
  GemmTile f, b, w;  // forward, input backward, weight gradient
};
inline GemmShapes gemm_shapes(const DeviceProfile& p, bool small, const GemmWidths& widths) {
  GemmShapes s;
  s.block_rows = small ? 1 : p.gemm_block_rows;
  s.block_cols = small ? 1 : p.gemm_block_cols;
  const int tile = small ? 16 : p.gemm_tile;
  s.f = gemm_tile(p, widths.fwd, tile, s.block_rows, s.block_cols);
  s.b = gemm_tile(p, widths.bwd_in, tile, s.block_rows, s.block_cols);
  s.w = gemm_tile(p, widths.wgt, tile, s.block_rows, s.block_cols);
  return s;
}

// The kernels' tile defines (gemm_tile.clh's BLK_R, BLK_C; TILE_K and per kernel FWD_, BIN_,
// WGT_ + TC and LR), appended to a program's feature defines.
inline std::string gemm_defines(const DeviceProfile& p, const GemmShapes& s) {
  const auto d = gemm_define;
  return d("TILE_K", p.gemm_tile_k) + d("BLK_R", s.block_rows) + d("BLK_C", s.block_cols) +
         d("FWD_TC", s.f.tc) + d("FWD_LR", s.f.lr) + d("BIN_TC", s.b.tc) + d("BIN_LR", s.b.lr) +
         d("WGT_TC", s.w.tc) + d("WGT_LR", s.w.lr);
}

// Local memory of the largest of the three kernels, in floats: the forward's a_tile[TR][K + 1]
// and w_tile[K][TC], the input backward's d_tile[TR][K + 1] and w_tile[K][TC + 1], the weight
// gradient's a_tile[K][TR + 1] and d_tile[K][TC], plus `tables` 4-byte entries per tile row
// (per depth slot in the weight gradient): the convolutions' pixel tables.
inline size_t gemm_local_floats(int tile_k, const GemmShapes& s, int tables) {
  const size_t k = size_t(tile_k), x = size_t(tables);
  return std::max({size_t(s.f.tr) * (k + 1) + k * s.f.tc + x * size_t(s.f.tr),
                   size_t(s.b.tr) * (k + 1) + k * (s.b.tc + 1) + x * size_t(s.b.tr),
                   k * (s.w.tr + 1) + k * s.w.tc + x * k});
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

// Launches a GEMM kernel over rows x cols with its tile's work-groups.
inline Event launch_gemm(Kernel& k, const GemmTile& t, size_t rows, size_t cols) {
  const auto g = t.global(rows, cols);
  return k.launch({g[0], g[1]}, {size_t(t.lc), size_t(t.lr)});
}
// The same over a third dimension of `chunks` (a weight gradient's chunks; 0: no launch).
inline Event launch_gemm_chunks(Kernel& k, const GemmTile& t, size_t rows, size_t cols,
                                size_t chunks) {
  const auto g = t.global(rows, cols);
  return k.launch({g[0], g[1], chunks}, {size_t(t.lc), size_t(t.lr), 1});
}

// Launches a weight gradient's chunk reduction (gemm_tile.clh's gemm_reduce_chunks) over
// `count` weights: work-groups of 16 weights x GEMM_REDUCE_LANES (16) lanes.
constexpr size_t kGemmReduceLanes = 16;
inline Event launch_gemm_reduce(Kernel& k, size_t count) {
  return k.launch({round_up(count, 16), kGemmReduceLanes}, {16, kGemmReduceLanes});
}

// A layer's three local_tiles GEMM kernels of one program, for the profile's register block
// (get(false), whose fit on the device is checked when built) and the 1 x 1 block of launches
// under gemm_min_work_items (get(true)), each built on first use.
class GemmKernels {
 public:
  struct Source {
    std::string what;              // the layer in errors ("Conv2d", "the MLP")
    std::string file;              // under kernels/
    std::string fwd, bwd_in, wgt;  // kernel names
    std::string opt;               // the layer's feature defines; the tile defines follow
    GemmWidths widths;
    int tables = 0;  // gemm_local_floats' per-row tables
  };
  struct Set {
    bool built = false;
    GemmShapes shapes;
    std::string opt;  // the program's options: Source::opt + gemm_defines
    Kernel fwd, bwd_in, wgt;
  };

  GemmKernels() = default;
  GemmKernels(Runtime& rt, const DeviceProfile& profile, Source src)
      : rt_(&rt), profile_(profile), src_(std::move(src)) {}

  Set& get(bool small) {
    Set& s = sets_[small ? 1 : 0];
    if (s.built) return s;
    if (!rt_) throw Error("cl::GemmKernels: not made with a Runtime");
    s.shapes = gemm_shapes(profile_, small, src_.widths);
    check_gemm_fit(*rt_, src_.what, gemm_local_floats(profile_.gemm_tile_k, s.shapes, src_.tables),
                   s.shapes.f, s.shapes.b, s.shapes.w);
    s.opt = src_.opt + gemm_defines(profile_, s.shapes);
    s.fwd = rt_->kernel(src_.file, src_.fwd, s.opt);
    s.bwd_in = rt_->kernel(src_.file, src_.bwd_in, s.opt);
    s.wgt = rt_->kernel(src_.file, src_.wgt, s.opt);
    s.built = true;
    return s;
  }
  // The profile's block's tiles (what a launch's size is judged by).
  const GemmShapes& main() { return get(false).shapes; }
  // The profile's block, or the 1 x 1 one when the profile's gives a launch of fewer than
  // gemm_min_work_items work-items.
  Set& pick(size_t work_items_main) {
    return get(work_items_main < size_t(profile_.gemm_min_work_items));
  }

 private:
  Runtime* rt_ = nullptr;
  DeviceProfile profile_;
  Source src_;
  Set sets_[2];
};

}  // namespace sgnlf::cl
