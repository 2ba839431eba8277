// Mlp's per-layer GEMM kernels, both variants of the device profile's `gemm` (mlp.hpp): the
// programs and their -D defines, and the launches of the forward, d_pre of the output layer,
// input backward, weight gradient and grouped sums (kernels/field/mlp.cl: cpu_tiles;
// kernels/field/mlp_tiles.cl: local_tiles, whose tile shapes, register blocks and launch sizes
// are cl/gemm_tiles.hpp's, shared with the convolutions).
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

size_t ceil_div(size_t a, size_t b) { return (a + b - 1) / b; }
}  // namespace

std::pair<std::string, std::string> Mlp::build_layer(Layer& L, int in_off, int prev_act,
                                                     bool prev_pre, bool group_bias,
                                                     bool towered) {
  const auto d = cl::gemm_define;
  const std::string features =
      d("N_IN", L.n_in) + d("IN_STRIDE", L.in_stride) + d("IN_OFFSET", in_off) +
      d("IN_PAD", pad16(L.n_in)) + d("OUT", L.out) + d("OUT_PAD", L.out_pad) +
      d("OUT_STRIDE", L.out_stride) + d("ACT", int(L.act)) + d("STORE_PRE", L.store_pre) +
      d("PREV_ACT", prev_act) + d("PREV_PRE", prev_pre) + d("DIN_STRIDE", L.in_stride) +
      d("DIN_OFFSET", in_off) + d("GROUP_BIAS", group_bias);
  const std::string towers = towered ? d("TOWER_IN", L.n_in / spec_.towers) +
                                           d("TOWER_OUT", L.out / spec_.towers)
                                     : std::string();
  if (local_tiles()) {
    cl::GemmKernels::Source src;
    src.what = "the MLP";
    src.file = "field/mlp_tiles.cl";
    src.fwd = "field_mlp_fwd";
    src.bwd_in = "field_mlp_bwd_in";
    src.wgt = "field_mlp_bwd_wgt";
    src.opt = features + d("HAS_BIAS", spec_.bias) + towers;
    src.widths = {L.out_pad, pad16(L.n_in), L.out_pad};
    L.gemm = cl::GemmKernels(rt_, profile_, src);
    // The profile's block (its fit checked here): its program holds every kernel.
    const std::string& f = src.file;
    const std::string opt = L.gemm.get(false).opt;
    L.bwd_out = rt_.kernel(f, "field_mlp_bwd_out", opt);
    L.reduce = rt_.kernel(f, "field_mlp_bwd_reduce", opt);
    if (group_bias) L.group_sum = rt_.kernel(f, "field_mlp_group_sum", opt);
    return {f, opt};
  }
  // The defines in mlp.cl's historical order (the cpu profile's programs are unchanged).
  const std::string opt = features + d("PTS", kPts) + d("ROWS", kRows) +
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
  const size_t cols = size_t(L.out_pad);
  auto& t = L.gemm.pick(L.gemm.main().f.work_items(size_t(n), cols));
  t.fwd.set_args(n, params, w_off, src, dst, pre, gbias, group, gidx, indexed);
  cl::launch_gemm(t.fwd, t.shapes.f, size_t(n), cols);
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
  auto& t = L.gemm.pick(L.gemm.main().b.work_items(size_t(n), in_pad));
  t.bwd_in.set_args(n, params, w_off, d_pre, prev, d_in);
  cl::launch_gemm(t.bwd_in, t.shapes.b, size_t(n), in_pad);
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
  const size_t cols = size_t(L.out_pad);
  auto& t = L.gemm.pick(L.gemm.main().w.work_items(w_rows, cols) * ch);
  t.wgt.set_args(rows, per, src, d_pre, partial_);
  cl::launch_gemm_chunks(t.wgt, t.shapes.w, w_rows, cols, ch);
  L.reduce.set_args(int(ch), partial_, grad, uint32_t(w_off));
  cl::launch_gemm_reduce(L.reduce, count);
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
