// Mlp's per-layer GEMM kernels, both variants of the device profile's `gemm` (mlp.hpp): the
// programs and their -D defines, the local_tiles tile shapes and the choice of register block,
// and the launches of the forward, d_pre of the output layer, input backward, weight gradient
// and grouped sums (kernels/field/mlp.cl: cpu_tiles; kernels/field/mlp_tiles.cl: local_tiles).
#include <algorithm>
#include <string>
#include <utility>

#include "cl/launch.hpp"
#include "core/error.hpp"
#include "field/mlp.hpp"

namespace sgnlf::field {
namespace {
// cpu_tiles (kernels/field/mlp.cl): its fixed shapes.
constexpr int kPts = 8;          // points per work-item in the GEMM kernels
constexpr int kRows = 16;        // weight rows per work-item in the weight gradient
constexpr int kMaxChunks = 256;  // weight-gradient partial sums (fixed for a given N)
constexpr int kMinChunk = 512;   // points per chunk at least (a chunk's rows stay in L2)
constexpr size_t kLocal = 16;    // work-group size along the point dimension
// local_tiles (kernels/field/mlp_tiles.cl): lanes of the weight gradient's reduction (its
// REDUCE_LANES) and weights per reduction work-group; local memory a tiled kernel may use at
// most (OpenCL 1.2's minimum for every device; the device's, where it has less).
constexpr size_t kReduceLanes = 16, kReduceWeights = 16;
constexpr size_t kMaxLocalBytes = 32 * 1024;

size_t ceil_div(size_t a, size_t b) { return (a + b - 1) / b; }
std::string define(const char* k, int v) { return std::string(" -D") + k + "=" + std::to_string(v); }
}  // namespace

size_t Mlp::TileShape::work_items(size_t rows, size_t cols) const {
  return ceil_div(rows, size_t(tr)) * size_t(lr) * ceil_div(cols, size_t(tc)) * size_t(lc);
}

std::pair<std::string, std::string> Mlp::build_layer(Layer& L, int in_off, int prev_act,
                                                     bool prev_pre, bool group_bias,
                                                     bool towered) {
  const auto d = define;
  L.opt = d("N_IN", L.n_in) + d("IN_STRIDE", L.in_stride) + d("IN_OFFSET", in_off) +
          d("IN_PAD", pad16(L.n_in)) + d("OUT", L.out) + d("OUT_PAD", L.out_pad) +
          d("OUT_STRIDE", L.out_stride) + d("ACT", int(L.act)) + d("STORE_PRE", L.store_pre) +
          d("PREV_ACT", prev_act) + d("PREV_PRE", prev_pre) + d("DIN_STRIDE", L.in_stride) +
          d("DIN_OFFSET", in_off) + d("GROUP_BIAS", group_bias);
  const std::string towers = towered ? d("TOWER_IN", L.n_in / spec_.towers) +
                                           d("TOWER_OUT", L.out / spec_.towers)
                                     : std::string();
  if (local_tiles()) {
    L.opt += d("HAS_BIAS", spec_.bias) + towers;
    Tiled& t = tiled(L, false);  // the profile's block: its program holds every kernel
    const std::string f = "field/mlp_tiles.cl";
    const std::string opt = L.opt + tile_defines(t);
    L.bwd_out = rt_.kernel(f, "field_mlp_bwd_out", opt);
    L.reduce = rt_.kernel(f, "field_mlp_bwd_reduce", opt);
    if (group_bias) L.group_sum = rt_.kernel(f, "field_mlp_group_sum", opt);
    return {f, opt};
  }
  // The defines in mlp.cl's historical order (the cpu profile's programs are unchanged).
  const std::string opt = L.opt + d("PTS", kPts) + d("ROWS", kRows) +
                          d("HAS_BIAS", spec_.bias) + towers;
  const std::string f = "field/mlp.cl";
  L.fwd = rt_.kernel(f, "field_mlp_fwd", opt);
  L.bwd_out = rt_.kernel(f, "field_mlp_bwd_out", opt);
  L.wgt = rt_.kernel(f, "field_mlp_bwd_wgt", opt);
  L.reduce = rt_.kernel(f, "field_mlp_bwd_reduce", opt);
  L.transpose = rt_.kernel(f, "field_mlp_transpose", opt);
  L.bwd_in = rt_.kernel(f, "field_mlp_bwd_in", opt);
  if (group_bias) L.group_sum = rt_.kernel(f, "field_mlp_group_sum", opt);
  return {f, opt};
}

Mlp::TileShape Mlp::tile_shape(int width, int tile, int block_rows, int block_cols) const {
  TileShape t;
  t.tc = std::min(tile, width);
  t.lc = t.tc / block_cols;
  t.lr = std::max(1, profile_.gemm_work_group / t.lc);
  t.tr = t.lr * block_rows;
  return t;
}

std::string Mlp::tile_defines(const Tiled& t) const {
  const auto d = define;
  return d("TILE_K", profile_.gemm_tile_k) + d("BLK_R", t.block_rows) +
         d("BLK_C", t.block_cols) + d("FWD_TC", t.f.tc) + d("FWD_LR", t.f.lr) +
         d("BIN_TC", t.b.tc) + d("BIN_LR", t.b.lr) + d("WGT_TC", t.w.tc) + d("WGT_LR", t.w.lr);
}

Mlp::Tiled& Mlp::tiled(Layer& L, bool small) {
  Tiled& t = L.tiled[small ? 1 : 0];
  if (t.built) return t;
  // The profile's block and tile, or a 1 x 1 block with 16-column tiles (small launches).
  t.block_rows = small ? 1 : profile_.gemm_block_rows;
  t.block_cols = small ? 1 : profile_.gemm_block_cols;
  const int tile = small ? 16 : profile_.gemm_tile;
  t.f = tile_shape(L.out_pad, tile, t.block_rows, t.block_cols);
  t.b = tile_shape(pad16(L.n_in), tile, t.block_rows, t.block_cols);
  t.w = tile_shape(L.out_pad, tile, t.block_rows, t.block_cols);
  // Local memory of each kernel (mlp_tiles.cl's tiles), in floats.
  const size_t k = size_t(profile_.gemm_tile_k);
  const size_t floats = std::max({size_t(t.f.tr) * (k + 1) + k * t.f.tc,
                                  size_t(t.b.tr) * (k + 1) + k * (t.b.tc + 1),
                                  k * (t.w.tr + 1) + k * t.w.tc});
  const auto& dev = rt_.device();
  const size_t local_bytes =
      dev.local_mem_bytes > 0 ? std::min<size_t>(kMaxLocalBytes, size_t(dev.local_mem_bytes))
                              : kMaxLocalBytes;
  if (floats * sizeof(float) > local_bytes)
    throw ConfigError("device profile '" + profile_.name + "': the MLP's local_tiles need " +
                      std::to_string(floats * sizeof(float)) + " bytes of local memory, more than " +
                      std::to_string(local_bytes) +
                      ": lower gemm_work_group, gemm_block_rows or gemm_tile_k");
  for (const TileShape* s : {&t.f, &t.b, &t.w})
    if (dev.max_work_group_size > 0 && size_t(s->lc) * size_t(s->lr) > dev.max_work_group_size)
      throw ConfigError("device profile '" + profile_.name + "': the MLP's local_tiles take " +
                        std::to_string(s->lc * s->lr) + " work-items per work-group, the device " +
                        std::to_string(dev.max_work_group_size) + ": lower gemm_work_group");
  const std::string opt = L.opt + tile_defines(t);
  const std::string f = "field/mlp_tiles.cl";
  t.fwd = rt_.kernel(f, "field_mlp_fwd", opt);
  t.bwd_in = rt_.kernel(f, "field_mlp_bwd_in", opt);
  t.wgt = rt_.kernel(f, "field_mlp_bwd_wgt", opt);
  t.built = true;
  return t;
}

Mlp::Tiled& Mlp::pick(Layer& L, size_t work_items_main) {
  return tiled(L, work_items_main < size_t(profile_.gemm_min_work_items));
}

size_t Mlp::chunks(size_t rows) const {
  if (local_tiles())
    return std::min<size_t>(size_t(profile_.gemm_max_chunks),
                            ceil_div(rows, size_t(profile_.gemm_chunk_points)));
  return std::min<size_t>(kMaxChunks, ceil_div(rows, kMinChunk));
}

void Mlp::launch_fwd(Layer& L, int n, const cl::Buffer& params, uint32_t w_off,
                     const cl::Buffer& src, cl::Buffer& dst, cl::Buffer& pre,
                     const cl::Buffer& gbias, int group, const cl::Buffer& gidx, int indexed) {
  if (!local_tiles()) {
    L.fwd.set_args(n, params, w_off, src, dst, pre, gbias, group, gidx, indexed);
    // One work-group covers all output tiles of its points: input rows are read once.
    L.fwd.launch({cl::round_up(ceil_div(size_t(n), kPts), kLocal), size_t(L.out_pad / 16)},
                 {kLocal, size_t(L.out_pad / 16)});
    return;
  }
  Tiled& t = pick(L, L.tiled[0].f.work_items(size_t(n), size_t(L.out_pad)));
  t.fwd.set_args(n, params, w_off, src, dst, pre, gbias, group, gidx, indexed);
  t.fwd.launch({ceil_div(size_t(L.out_pad), size_t(t.f.tc)) * size_t(t.f.lc),
                ceil_div(size_t(n), size_t(t.f.tr)) * size_t(t.f.lr)},
               {size_t(t.f.lc), size_t(t.f.lr)});
}

void Mlp::launch_bwd_in(Layer& L, int n, const cl::Buffer& params, uint32_t w_off,
                        const cl::Buffer& d_pre, const cl::Buffer& prev, cl::Buffer& d_in) {
  const size_t in_pad = size_t(pad16(L.n_in));
  if (!local_tiles()) {
    L.transpose.set_args(params, w_off, wt_);
    L.transpose.launch({in_pad, size_t(L.out_pad)});
    L.bwd_in.set_args(n, wt_, d_pre, prev, d_in);
    L.bwd_in.launch({cl::round_up(ceil_div(size_t(n), kPts), kLocal), in_pad / 16},
                    {kLocal, in_pad / 16});
    return;
  }
  // W_t is read transposed into local memory: no transpose kernel.
  Tiled& t = pick(L, L.tiled[0].b.work_items(size_t(n), in_pad));
  t.bwd_in.set_args(n, params, w_off, d_pre, prev, d_in);
  t.bwd_in.launch({ceil_div(in_pad, size_t(t.b.tc)) * size_t(t.b.lc),
                   ceil_div(size_t(n), size_t(t.b.tr)) * size_t(t.b.lr)},
                  {size_t(t.b.lc), size_t(t.b.lr)});
}

void Mlp::weight_grad(Layer& L, const cl::Buffer& src, const cl::Buffer& d_pre, int rows,
                      cl::Buffer& grad, size_t w_off) {
  const size_t ch = chunks(size_t(rows));
  const int per = int(ceil_div(size_t(rows), ch));
  const size_t count = size_t(L.n_in + 1) * L.out_pad;
  if (!local_tiles()) {
    L.wgt.set_args(rows, per, src, d_pre, partial_);
    // One work-group per chunk: all row blocks and output tiles reuse the chunk from cache.
    const size_t row_blocks = ceil_div(size_t(L.n_in), kRows) + 1;
    L.wgt.launch({ch, row_blocks, size_t(L.out_pad / 16)}, {1, row_blocks, size_t(L.out_pad / 16)});
    L.reduce.set_args(int(ch), partial_, grad, uint32_t(w_off));
    cl::launch_1d(L.reduce, count);
    return;
  }
  const size_t w_rows = size_t(L.n_in + 1);  // the inputs and the bias row
  Tiled& t = pick(L, L.tiled[0].w.work_items(w_rows, size_t(L.out_pad)) * ch);
  t.wgt.set_args(rows, per, src, d_pre, partial_);
  t.wgt.launch({ceil_div(size_t(L.out_pad), size_t(t.w.tc)) * size_t(t.w.lc),
                ceil_div(w_rows, size_t(t.w.tr)) * size_t(t.w.lr), ch},
               {size_t(t.w.lc), size_t(t.w.lr), 1});
  L.reduce.set_args(int(ch), partial_, grad, uint32_t(w_off));
  L.reduce.launch({cl::round_up(count, kReduceWeights), kReduceLanes},
                  {kReduceWeights, kReduceLanes});
}

void Mlp::launch_bwd_out(Layer& L, int n, const cl::Buffer& d_out, const cl::Buffer& y,
                         cl::Buffer& d_pre) {
  L.bwd_out.set_args(n, d_out, y, d_pre);
  // cpu_tiles: a work-item per point (16 columns at a time); local_tiles: per element.
  cl::launch_1d(L.bwd_out, size_t(n) * (local_tiles() ? size_t(L.out_pad) : 1));
}

void Mlp::launch_group_sum(Layer& L, int ng, int group, const cl::Buffer& d_pre,
                           cl::Buffer& d_group, const cl::Buffer& offsets, int indexed) {
  L.group_sum.set_args(ng, group, d_pre, d_group, offsets, indexed);
  if (local_tiles()) {  // a work-item per (group, column)
    cl::launch_1d(L.group_sum, size_t(ng) * size_t(L.out_pad));
    return;
  }
  L.group_sum.launch({cl::round_up(size_t(ng), 16), size_t(L.out_pad / 16)},
                     {16, size_t(L.out_pad / 16)});
}

}  // namespace sgnlf::field
