// TimeHashGrid host launcher: plane and level tables, parameter init, validation of shapes and
// the enqueueing of the kernels in kernels/field/hashgrid_time.cl.
#include "field/time_hash_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "cl/launch.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf::field {

std::vector<TimeHashPlane> time_hash_grid_planes(const TimeHashGridConfig& cfg) {
  cfg.validate();
  const int log2_table[3] = {cfg.log2_table_xy, cfg.log2_table_xz, cfg.log2_table_yz};
  std::vector<TimeHashPlane> out(3);
  uint64_t offset = 0;
  for (int p = 0; p < 3; ++p) {
    const uint64_t table = uint64_t(1) << log2_table[p];
    uint64_t in_slice = 0;
    for (int l = 0; l < cfg.levels; ++l) {
      HashGridLevel lv{};
      lv.scale =
          float(double(cfg.base_resolution) * std::pow(double(cfg.per_level_scale), l) - 1.0);
      lv.res = uint32_t(std::ceil(double(lv.scale))) + 2u;
      const uint64_t dense = uint64_t(lv.res) * lv.res;
      lv.size = uint32_t(std::min(table, (dense + 7) / 8 * 8));
      lv.hashed = dense > table ? 1u : 0u;
      lv.offset = uint32_t(in_slice);
      in_slice += lv.size;
      out[size_t(p)].levels.push_back(lv);
    }
    out[size_t(p)].offset = uint32_t(offset);
    out[size_t(p)].slice_entries = uint32_t(in_slice);
    offset += in_slice * uint64_t(cfg.time_slices);
    if (offset * uint64_t(cfg.features) >= (uint64_t(1) << 31))
      throw ConfigError("time_hash_grid: parameter count exceeds 2^31 floats");
  }
  return out;
}

TimeHashGrid::TimeHashGrid(cl::Runtime& rt, const TimeHashGridConfig& cfg)
    : rt_(rt), cfg_(cfg), planes_(time_hash_grid_planes(cfg)) {
  n_params_ = (size_t(planes_[2].offset) +
               size_t(planes_[2].slice_entries) * size_t(cfg_.time_slices)) *
              size_t(cfg_.features);
  std::vector<float> scale;
  std::vector<uint32_t> meta, pmeta;
  for (const auto& lv : planes_[0].levels) scale.push_back(lv.scale);
  for (const auto& p : planes_) {
    pmeta.insert(pmeta.end(), {p.offset, p.slice_entries});
    for (const auto& lv : p.levels)
      meta.insert(meta.end(), {lv.res, lv.offset, lv.size, lv.hashed});
  }
  scale_ = cl::Buffer::from(rt_, scale);
  meta_ = cl::Buffer::from(rt_, meta);
  pmeta_ = cl::Buffer::from(rt_, pmeta);
  chunk_ = cfg_.chunk > 0 ? cfg_.chunk : rt_.device_profile().plane_chunk;
  variant_ = rt_.device_profile().encoder_backward;
  const std::string opt = "-DLEVELS=" + std::to_string(cfg_.levels) +
                          " -DFEATURES=" + std::to_string(cfg_.features) +
                          " -DSLICES=" + std::to_string(cfg_.time_slices) +
                          " -DCHUNK=" + std::to_string(chunk_);
  const std::string file = "field/hashgrid_time.cl";
  fwd_ = rt_.kernel(file, "field_hashgrid_time_fwd", opt);
  bwd_ = rt_.kernel(file, "field_hashgrid_time_bwd", opt);
  dx_reduce_ = rt_.kernel(file, "field_hashgrid_time_dx_reduce", opt);
  blend_ = rt_.kernel(file, "field_hashgrid_time_blend", opt);
  spread_ = rt_.kernel(file, "field_hashgrid_time_spread", opt);
  zero_ = rt_.kernel(file, "field_hashgrid_time_zero", opt);
  const std::string opt1 = "-DLEVELS=" + std::to_string(cfg_.levels) +
                           " -DFEATURES=" + std::to_string(cfg_.features) +
                           " -DSLICES=1 -DCHUNK=" + std::to_string(chunk_);
  fwd1_ = rt_.kernel(file, "field_hashgrid_time_fwd", opt1);
  bwd1_ = rt_.kernel(file, "field_hashgrid_time_bwd", opt1);
  bwd_points_ = rt_.kernel(file, "field_hashgrid_time_bwd_points", opt);
  bwd_points1_ = rt_.kernel(file, "field_hashgrid_time_bwd_points", opt1);
  std::vector<uint32_t> bmeta, pmeta1;
  uint32_t entries = 0;
  for (const auto& p : planes_) {
    bmeta.push_back(entries);
    pmeta1.insert(pmeta1.end(), {entries, p.slice_entries});
    entries += p.slice_entries;
  }
  blend_entries_ = int(entries);
  bmeta_ = cl::Buffer::from(rt_, bmeta);
  pmeta1_ = cl::Buffer::from(rt_, pmeta1);
  blended_ = cl::Buffer(rt_, size_t(entries) * size_t(cfg_.features) * sizeof(float));
  g_blended_ = cl::Buffer(rt_, size_t(entries) * size_t(cfg_.features) * sizeof(float));
}

void TimeHashGrid::init_params(std::vector<float>& host_params, size_t offset,
                               uint64_t seed) const {
  if (offset + n_params_ > host_params.size())
    throw Error("TimeHashGrid::init_params: slice [" + std::to_string(offset) + ", +" +
                std::to_string(n_params_) + ") exceeds buffer of " +
                std::to_string(host_params.size()));
  Rng rng(seed, 0x7468u);
  for (size_t i = 0; i < n_params_; ++i) host_params[offset + i] = rng.uniform(-1e-4f, 1e-4f);
}

static void check_bytes(const cl::Buffer& b, size_t floats, const char* what) {
  if (b.bytes() < floats * sizeof(float))
    throw Error(std::string("TimeHashGrid: buffer '") + what + "' has " +
                std::to_string(b.bytes()) + " bytes, needs " +
                std::to_string(floats * sizeof(float)));
}

void TimeHashGrid::check(const cl::Buffer& params, size_t offset, const cl::Buffer& x,
                         const cl::Buffer* t, int n, const cl::Buffer& enc, int stride, int col,
                         const char* what) const {
  if (n < 0) throw Error("TimeHashGrid: negative point count " + std::to_string(n));
  if (col < 0 || col + n_output() > stride)
    throw Error("TimeHashGrid: columns [" + std::to_string(col) + ", +" +
                std::to_string(n_output()) + ") do not fit a row of " + std::to_string(stride));
  check_bytes(params, offset + n_params_, "params");
  check_bytes(x, size_t(n) * 3, "x");
  if (t) check_bytes(*t, size_t(n), "t");
  if (n > 0) check_bytes(enc, size_t(n - 1) * size_t(stride) + size_t(col + n_output()), what);
}

void TimeHashGrid::forward(const cl::Buffer& params, size_t offset, const cl::Buffer& x,
                           const cl::Buffer& t, int n, cl::Buffer& enc, int stride, int col) {
  if (stride == 0) stride = n_output();
  check(params, offset, x, &t, n, enc, stride, col, "enc");
  if (n == 0) return;
  fwd_.set_args(n, params, uint32_t(offset), x, t, scale_, meta_, pmeta_, enc, stride, col);
  launch_points(fwd_, n);
}

void TimeHashGrid::backward(const cl::Buffer& params, size_t offset, const cl::Buffer& x,
                            const cl::Buffer& t, int n, const cl::Buffer& d_enc,
                            cl::Buffer& grad, size_t grad_offset, cl::Buffer* d_x,
                            bool accumulate, int stride, int col) {
  if (stride == 0) stride = n_output();
  check(params, offset, x, &t, n, d_enc, stride, col, "d_enc");
  check_bytes(grad, grad_offset + n_params_, "grad");
  const bool dx = d_x && n > 0;
  if (dx) ensure_dx_part(n);
  if (d_x) check_bytes(*d_x, size_t(n) * 3, "d_x");
  const cl::Buffer& part = dx ? dx_part_ : scale_;  // without d_x never written
  if (variant_ == cl::EncoderBackward::Serial) {
    bwd_.set_args(n, params, uint32_t(offset), x, t, scale_, meta_, pmeta_, d_enc, stride, col,
                  grad, uint32_t(grad_offset), accumulate ? 1 : 0, dx ? 1 : 0, part);
    bwd_.launch({size_t(cfg_.levels)}, {1});
  } else if (variant_ == cl::EncoderBackward::Atomic) {
    if (!accumulate) {
      zero_.set_args(uint32_t(n_params_), grad, uint32_t(grad_offset));
      cl::launch_1d(zero_, n_params_);
    }
    // The pair buffers are not written by the atomic form: any buffer stands in for them.
    bwd_points_.set_args(n, params, uint32_t(offset), x, t, scale_, meta_, pmeta_, d_enc, stride,
                         col, 1, meta_, meta_, scale_, scale_, grad, uint32_t(grad_offset),
                         dx ? 1 : 0, part);
    cl::launch_rows(bwd_points_, size_t(n), size_t(cfg_.levels));
  } else {
    EntryReduction& r = reduction(false);
    r.reserve(n);
    if (n > 0) {
      bwd_points_.set_args(n, params, uint32_t(offset), x, t, scale_, meta_, pmeta_, d_enc,
                           stride, col, 0, r.keys(), r.vals(), r.coef(), r.vec(), grad,
                           uint32_t(grad_offset), dx ? 1 : 0, part);
      cl::launch_rows(bwd_points_, size_t(n), size_t(cfg_.levels));
    }
    r.reduce(n, grad, grad_offset, accumulate);
  }
  if (!dx) return;
  dx_reduce_.set_args(n, dx_part_, *d_x);
  cl::launch_1d(dx_reduce_, size_t(n));
}

EntryReduction& TimeHashGrid::reduction(bool one_slice) {
  auto& r = one_slice ? reduction1_ : reduction_;
  if (r) return *r;
  // Unit = level: level l of every plane and time slice (of the one-slice table: one slice).
  std::vector<EntryRange> ranges;
  uint32_t first1 = 0;
  for (int p = 0; p < 3; ++p) {
    const TimeHashPlane& pl = planes_[size_t(p)];
    for (int l = 0; l < cfg_.levels; ++l) {
      const HashGridLevel& lv = pl.levels[size_t(l)];
      if (one_slice) {
        ranges.push_back({uint32_t(l), first1 + lv.offset, lv.size});
      } else {
        for (int s = 0; s < cfg_.time_slices; ++s)
          ranges.push_back({uint32_t(l), pl.offset + uint32_t(s) * pl.slice_entries + lv.offset,
                            lv.size});
      }
    }
    first1 += pl.slice_entries;
  }
  const int slots = one_slice || cfg_.time_slices == 1 ? 1 : 2;
  r = std::make_unique<EntryReduction>(rt_, cfg_.features, cfg_.levels, 12 * slots, 4 * slots,
                                       std::move(ranges));
  return *r;
}

void TimeHashGrid::ensure_dx_part(int n) {
  const size_t part = size_t(n) * size_t(cfg_.levels) * 3;
  if (dx_part_floats_ < part) {
    dx_part_ = cl::Buffer(rt_, part * sizeof(float));
    dx_part_floats_ = part;
  }
}

void TimeHashGrid::blend(const cl::Buffer& params, size_t offset, float t) {
  if (!std::isfinite(t))
    throw Error("TimeHashGrid: time " + std::to_string(t) + " is not a finite number");
  blend_.set_args(blend_entries_, t, params, uint32_t(offset), pmeta_, bmeta_, blended_);
  cl::launch_1d(blend_, size_t(blend_entries_));
}

void TimeHashGrid::forward_at(const cl::Buffer& params, size_t offset, const cl::Buffer& x,
                              float t, int n, cl::Buffer& enc, int stride, int col) {
  if (stride == 0) stride = n_output();
  check(params, offset, x, nullptr, n, enc, stride, col, "enc");
  if (n == 0) return;
  blend(params, offset, t);
  // The one-slice build never reads its t argument: x stands in for it.
  fwd1_.set_args(n, blended_, 0u, x, x, scale_, meta_, pmeta1_, enc, stride, col);
  launch_points(fwd1_, n);
}

void TimeHashGrid::backward_at(const cl::Buffer& params, size_t offset, const cl::Buffer& x,
                               float t, int n, const cl::Buffer& d_enc, cl::Buffer& grad,
                               size_t grad_offset, cl::Buffer* d_x, bool accumulate, int stride,
                               int col) {
  if (stride == 0) stride = n_output();
  check(params, offset, x, nullptr, n, d_enc, stride, col, "d_enc");
  check_bytes(grad, grad_offset + n_params_, "grad");
  if (d_x) check_bytes(*d_x, size_t(n) * 3, "d_x");
  if (!accumulate) {
    zero_.set_args(uint32_t(n_params_), grad, uint32_t(grad_offset));
    cl::launch_1d(zero_, n_params_);
  }
  if (n == 0) return;
  const bool dx = d_x != nullptr;
  if (dx) ensure_dx_part(n);
  blend(params, offset, t);  // the table the forward read
  const cl::Buffer& part = dx ? dx_part_ : scale_;  // without d_x never written
  if (variant_ == cl::EncoderBackward::Serial) {
    bwd1_.set_args(n, blended_, 0u, x, x, scale_, meta_, pmeta1_, d_enc, stride, col,
                   g_blended_, 0u, 0, dx ? 1 : 0, part);
    bwd1_.launch({size_t(cfg_.levels)}, {1});
  } else if (variant_ == cl::EncoderBackward::Atomic) {
    const size_t floats = size_t(blend_entries_) * size_t(cfg_.features);
    zero_.set_args(uint32_t(floats), g_blended_, 0u);
    cl::launch_1d(zero_, floats);
    bwd_points1_.set_args(n, blended_, 0u, x, x, scale_, meta_, pmeta1_, d_enc, stride, col, 1,
                          meta_, meta_, scale_, scale_, g_blended_, 0u, dx ? 1 : 0, part);
    cl::launch_rows(bwd_points1_, size_t(n), size_t(cfg_.levels));
  } else {
    EntryReduction& r = reduction(true);
    r.reserve(n);
    bwd_points1_.set_args(n, blended_, 0u, x, x, scale_, meta_, pmeta1_, d_enc, stride, col, 0,
                          r.keys(), r.vals(), r.coef(), r.vec(), g_blended_, 0u, dx ? 1 : 0,
                          part);
    cl::launch_rows(bwd_points1_, size_t(n), size_t(cfg_.levels));
    r.reduce(n, g_blended_, 0, false);
  }
  spread_.set_args(blend_entries_, t, pmeta_, bmeta_, g_blended_, grad, uint32_t(grad_offset));
  cl::launch_1d(spread_, size_t(blend_entries_));
  if (!dx) return;
  dx_reduce_.set_args(n, dx_part_, *d_x);
  cl::launch_1d(dx_reduce_, size_t(n));
}

void TimeHashGrid::launch_points(cl::Kernel& k, int n) {
  const size_t items = (size_t(n) + size_t(chunk_) - 1) / size_t(chunk_);
  if (chunk_ == 1)
    cl::launch_rows(k, items, size_t(cfg_.levels));
  else
    k.launch({items, size_t(cfg_.levels)}, {1, 1});
}

}  // namespace sgnlf::field
