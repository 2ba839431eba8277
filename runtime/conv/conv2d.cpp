// Conv2d host launcher: programs specialised by -D defines, parameter init, shape checks and
// the enqueueing of forward and backward passes (kernels/conv/conv2d.cl).
#include "conv/conv2d.hpp"

#include <algorithm>
#include <string>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf::conv {
namespace {
constexpr int kPts = 8;            // pixels per work-item (forward, input backward)
constexpr int kRows = 16;          // weight rows per work-item in the weight gradient
constexpr int kMaxChunks = 256;    // weight-gradient partial sums at most
constexpr int kMinChunk = 256;     // output pixels per chunk at least
constexpr size_t kMaxPartial = size_t(4) << 20;  // floats of partial sums at most (16 MiB)
constexpr size_t kLocalTiles = 16;  // work-group size along the pixel-tile dimension
constexpr size_t kLocalRows = 8;    // row blocks per work-group in the weight gradient

constexpr size_t kMaxLocal = 256;   // work-group size at most (fits common GPU limits)

size_t ceil_div(size_t a, size_t b) { return (a + b - 1) / b; }
// Work-group extent along the tile dimension when `blocks` channel blocks share a group.
size_t tile_local(size_t base, size_t blocks) { return std::max<size_t>(1, std::min(base, kMaxLocal / blocks)); }
int pad16(int c) { return (c + 15) / 16 * 16; }

void check_bytes(const cl::Buffer& b, size_t floats, const char* what) {
  if (b.bytes() < floats * sizeof(float))
    throw Error(std::string("Conv2d: buffer '") + what + "' has " + std::to_string(b.bytes()) +
                " bytes, needs " + std::to_string(floats * sizeof(float)));
}
}  // namespace

void Conv2dSpec::validate() const {
  check_range("conv2d", "c_in", c_in, 1, 1024);
  check_range("conv2d", "c_out", c_out, 1, 1024);
  check_range("conv2d", "kernel", kernel, 1, 7);
  check_range("conv2d", "stride", stride, 1, 4);
  check_range("conv2d", "pad", pad, 0, kernel - 1);
  if (in_cs != 0 && in_cs < c_in)
    throw ConfigError("conv2d: 'in_cs' = " + std::to_string(in_cs) + " is below c_in = " +
                      std::to_string(c_in));
}

int Conv2dSpec::input_cs() const {
  if (in_cs > 0) return in_cs;
  return c_in >= 16 ? pad16(c_in) : c_in;
}

Conv2d::Conv2d(cl::Runtime& rt, const Conv2dSpec& spec)
    : rt_(rt), spec_(spec), profile_(rt.device_profile()) {
  spec_.validate();
  tiles_ = profile_.gemm == cl::GemmVariant::LocalTiles;
  auto d = [](const char* k, int v) { return std::string(" -D") + k + "=" + std::to_string(v); };
  const std::string opt = d("C_IN", spec_.c_in) + d("IN_CS", spec_.input_cs()) +
                          d("IN_PAD", pad16(spec_.c_in)) + d("C_OUT", spec_.c_out) +
                          d("O_PAD", spec_.out_cs()) + d("K", spec_.kernel) +
                          d("S", spec_.stride) + d("P", spec_.pad) + d("PTS", kPts) +
                          d("ROWS", kRows);
  if (tiles_) {  // local_tiles: kernels/conv/conv2d_tiles.cl (the 1 x 1 block on first use)
    cl::GemmKernels::Source src;
    src.what = "Conv2d";
    src.file = "conv/conv2d_tiles.cl";
    src.fwd = "conv2d_fwd_tiles";
    src.bwd_in = "conv2d_bwd_in_tiles";
    src.wgt = "conv2d_bwd_wgt_tiles";
    src.opt = d("C_IN", spec_.c_in) + d("IN_CS", spec_.input_cs()) +
              d("IN_PAD", pad16(spec_.c_in)) + d("C_OUT", spec_.c_out) +
              d("O_PAD", spec_.out_cs()) + d("K", spec_.kernel) + d("S", spec_.stride) +
              d("P", spec_.pad);
    src.widths = {spec_.out_cs(), pad16(spec_.c_in), spec_.out_cs()};
    src.tables = 3;  // pixel tables: image offset, y and x per tile row (per pixel slot)
    gemm_ = cl::GemmKernels(rt_, profile_, src);
    // The profile's tiles checked against the device here.
    reduce_tiles_ = rt_.kernel(src.file, "conv2d_bwd_reduce_tiles", gemm_.get(false).opt);
    return;
  }
  const std::string f = "conv/conv2d.cl", fn = "conv/conv2d_narrow.cl";
  // Must match the guards of kernels/conv/conv2d_narrow.cl.
  narrow_ = spec_.c_out <= 2 && spec_.c_in % 16 == 0 && spec_.input_cs() % 16 == 0;
  fwd_ = narrow_ ? rt_.kernel(fn, "conv2d_fwd_narrow", opt) : rt_.kernel(f, "conv2d_fwd", opt);
  transpose_ = rt_.kernel(f, "conv2d_transpose", opt);
  // Must match the C_IN <= 4 guard of conv2d_bwd_in_narrow (kernels/conv/conv2d_narrow.cl).
  narrow_in_ = spec_.c_in <= 4;
  bwd_in_ = narrow_in_ ? rt_.kernel(fn, "conv2d_bwd_in_narrow", opt)
                       : rt_.kernel(f, "conv2d_bwd_in", opt);
  bwd_wgt_ = narrow_ ? rt_.kernel(fn, "conv2d_bwd_wgt_narrow", opt)
                    : rt_.kernel(f, "conv2d_bwd_wgt", opt);
  reduce_ = rt_.kernel(f, "conv2d_bwd_reduce", opt);
  const size_t zeros = size_t(std::max({spec_.input_cs(), spec_.out_cs(), 16}));
  zeros_ = cl::Buffer::from(rt_, std::vector<float>(zeros, 0.0f));
  wt_ = cl::Buffer(rt_, size_t(spec_.kernel) * spec_.kernel * spec_.c_out * pad16(spec_.c_in) *
                            sizeof(float));
}

void Conv2d::init_params(std::vector<float>& host_params, size_t offset, uint64_t seed,
                         float stddev) const {
  if (offset + n_params() > host_params.size())
    throw Error("Conv2d::init_params: slice [" + std::to_string(offset) + ", +" +
                std::to_string(n_params()) + ") exceeds buffer of " +
                std::to_string(host_params.size()) + " floats");
  Rng rng(seed, 0x4356u);
  const int rows = spec_.kernel * spec_.kernel * spec_.c_in, oc = spec_.out_cs();
  float* w = host_params.data() + offset;
  for (int r = 0; r <= rows; ++r)
    for (int o = 0; o < oc; ++o) {
      const float g = float(rng.normal()) * stddev;  // drawn for every slot: layout-stable
      w[size_t(r) * oc + o] = (r < rows && o < spec_.c_out) ? g : 0.0f;
    }
}

void Conv2d::check_shape(int n, int h, int w, const char* where) const {
  if (n < 1 || h < 1 || w < 1)
    throw Error(std::string("Conv2d::") + where + ": bad input shape n = " + std::to_string(n) +
                ", h = " + std::to_string(h) + ", w = " + std::to_string(w));
  if (spec_.out_size(h) < 1 || spec_.out_size(w) < 1)
    throw Error(std::string("Conv2d::") + where + ": input " + std::to_string(h) + " x " +
                std::to_string(w) + " is too small for kernel " + std::to_string(spec_.kernel) +
                ", stride " + std::to_string(spec_.stride) + ", pad " + std::to_string(spec_.pad));
}

int Conv2d::wgrad_chunks(int pixels) const {
  const size_t per_chunk = size_t(spec_.kernel * spec_.kernel * spec_.c_in + 1) * spec_.out_cs();
  size_t ch = tiles_ ? std::min<size_t>(size_t(profile_.gemm_max_chunks),
                                        ceil_div(size_t(pixels), size_t(profile_.gemm_chunk_points)))
                     : std::min<size_t>(kMaxChunks, ceil_div(size_t(pixels), kMinChunk));
  ch = std::min(ch, std::max<size_t>(1, kMaxPartial / per_chunk));
  return int(std::max<size_t>(ch, 1));
}

void Conv2d::forward(const cl::Buffer& params, size_t offset, const cl::Buffer& in, int n, int h,
                     int w, cl::Buffer& out, cl::Buffer* act_out, float slope) {
  check_shape(n, h, w, "forward");
  const int ho = spec_.out_size(h), wo = spec_.out_size(w);
  check_bytes(params, offset + n_params(), "params");
  check_bytes(in, size_t(n) * h * w * spec_.input_cs(), "in");
  check_bytes(out, size_t(n) * ho * wo * spec_.out_cs(), "out");
  if (act_out) {
    check_bytes(*act_out, size_t(n) * ho * wo * spec_.out_cs(), "act_out");
    check_range("conv2d", "slope", slope, 0.0f, 1.0f);
  }
  if (tiles_) {
    const size_t pixels = size_t(n) * ho * wo, cols = size_t(spec_.out_cs());
    auto& t = gemm_.pick(gemm_.main().f.work_items(pixels, cols));
    t.fwd.set_args(n, h, w, ho, wo, params, uint32_t(offset), in, out, int(act_out != nullptr),
                   slope, act_out ? *act_out : out);
    cl::launch_gemm(t.fwd, t.shapes.f, pixels, cols);
    return;
  }
  const size_t tiles = size_t(n) * ho * ceil_div(size_t(wo), kPts);
  const size_t oblocks = size_t(spec_.out_cs() / 16);
  if (narrow_) {
    transpose_.set_args(params, uint32_t(offset), wt_);
    transpose_.launch({size_t(spec_.c_in), size_t(spec_.c_out),
                       size_t(spec_.kernel) * spec_.kernel});
    fwd_.set_args(n, h, w, ho, wo, params, uint32_t(offset), wt_, in, out, zeros_,
                  int(act_out != nullptr), slope, act_out ? *act_out : out);
    fwd_.launch({cl::round_up(tiles, kLocalTiles)}, {kLocalTiles});
    return;
  }
  fwd_.set_args(n, h, w, ho, wo, params, uint32_t(offset), in, out, zeros_, int(act_out != nullptr),
                slope, act_out ? *act_out : out);
  const size_t lt = tile_local(kLocalTiles, oblocks);
  fwd_.launch({cl::round_up(tiles, lt), oblocks}, {lt, oblocks});
}

void Conv2d::backward(const cl::Buffer& params, size_t offset, const cl::Buffer& in, int n,
                      int h, int w, const cl::Buffer& d_out, cl::Buffer* grad,
                      size_t grad_offset, cl::Buffer* d_in) {
  check_shape(n, h, w, "backward");
  const int ho = spec_.out_size(h), wo = spec_.out_size(w);
  check_bytes(params, offset + n_params(), "params");
  check_bytes(in, size_t(n) * h * w * spec_.input_cs(), "in");
  check_bytes(d_out, size_t(n) * ho * wo * spec_.out_cs(), "d_out");
  const size_t oblocks = size_t(spec_.out_cs() / 16);
  if (grad) {
    check_bytes(*grad, grad_offset + n_params(), "grad");
    const int pixels = n * ho * wo;
    const int chunks = wgrad_chunks(pixels);
    const int per = int(ceil_div(size_t(pixels), size_t(chunks)));
    const size_t count = n_params();
    if (partial_floats_ < size_t(chunks) * count) {
      partial_ = cl::Buffer(rt_, size_t(chunks) * count * sizeof(float));
      partial_floats_ = size_t(chunks) * count;
    }
    if (tiles_) {
      const size_t w_rows = size_t(spec_.kernel) * spec_.kernel * spec_.c_in + 1;  // + bias
      const size_t cols = size_t(spec_.out_cs());
      auto& t = gemm_.pick(gemm_.main().w.work_items(w_rows, cols) * size_t(chunks));
      t.wgt.set_args(n, h, w, ho, wo, per, in, d_out, partial_);
      cl::launch_gemm_chunks(t.wgt, t.shapes.w, w_rows, cols, size_t(chunks));
      reduce_tiles_.set_args(chunks, partial_, *grad, uint32_t(grad_offset));
      cl::launch_gemm_reduce(reduce_tiles_, count);
    } else {
      const size_t rows = size_t(spec_.kernel) * spec_.kernel * spec_.c_in;
      const size_t row_blocks = ceil_div(rows, kRows) + 1;  // + the bias row block
      bwd_wgt_.set_args(n, h, w, ho, wo, per, in, d_out, partial_);
      if (narrow_) {
        const size_t groups = size_t(spec_.kernel) * spec_.kernel * (spec_.c_in / 16) + 1;
        bwd_wgt_.launch({size_t(chunks), cl::round_up(groups, kLocalRows)}, {1, kLocalRows});
      } else {
        const size_t lr = tile_local(kLocalRows, oblocks);
        bwd_wgt_.launch({size_t(chunks), cl::round_up(row_blocks, lr), oblocks}, {1, lr, oblocks});
      }
      reduce_.set_args(chunks, partial_, *grad, uint32_t(grad_offset));
      reduce_.launch({cl::round_up(count, 64)}, {64});
    }
  }
  if (d_in) {
    check_bytes(*d_in, size_t(n) * h * w * spec_.input_cs(), "d_in");
    const int ip = pad16(spec_.c_in), taps = spec_.kernel * spec_.kernel;
    const int s = spec_.stride;
    if (tiles_) {
      // Rows: the S² residue classes of input pixels, each n · ceil(h / S) · ceil(w / S) slots.
      const size_t per_class = size_t(n) * ceil_div(size_t(h), size_t(s)) *
                               ceil_div(size_t(w), size_t(s));
      const size_t main_items = size_t(s) * s * gemm_.main().b.work_items(per_class, size_t(ip));
      auto& t = gemm_.pick(main_items);
      t.bwd_in.set_args(n, h, w, ho, wo, params, uint32_t(offset), d_out, *d_in);
      const auto g = t.shapes.b.global(per_class, size_t(ip));
      t.bwd_in.launch({g[0], size_t(s) * s * g[1]}, {size_t(t.shapes.b.lc), size_t(t.shapes.b.lr)});
      return;
    }
    const size_t txr = ceil_div(ceil_div(size_t(w), size_t(s)), kPts);
    const size_t tiles = size_t(n) * h * s * txr;
    if (narrow_in_) {
      bwd_in_.set_args(n, h, w, ho, wo, params, uint32_t(offset), d_out, *d_in, zeros_);
      bwd_in_.launch({cl::round_up(tiles, kLocalTiles)}, {kLocalTiles});
      return;
    }
    transpose_.set_args(params, uint32_t(offset), wt_);
    transpose_.launch({size_t(ip), size_t(spec_.c_out), size_t(taps)});
    const size_t iblocks = size_t(ip / 16);
    bwd_in_.set_args(n, h, w, ho, wo, wt_, d_out, *d_in, zeros_);
    const size_t lt = tile_local(kLocalTiles, iblocks);
    bwd_in_.launch({cl::round_up(tiles, lt), iblocks}, {lt, iblocks});
  }
}

}  // namespace sgnlf::conv
