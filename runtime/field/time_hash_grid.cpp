// TimeHashGrid host launcher: plane and level tables, parameter init, validation of shapes and
// the enqueueing of the kernels in kernels/field/hashgrid_time.cl.
#include "field/time_hash_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

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
  chunk_ = cfg_.chunk > 0 ? cfg_.chunk : (rt_.device().type == "CPU" ? 64 : 1);
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
  bwd_.set_args(n, params, uint32_t(offset), x, t, scale_, meta_, pmeta_, d_enc, stride, col,
                grad, uint32_t(grad_offset), accumulate ? 1 : 0, dx ? 1 : 0,
                dx ? dx_part_ : scale_);  // without d_x the part argument is never written
  bwd_.launch({size_t(cfg_.levels)}, {1});
  if (!dx) return;
  dx_reduce_.set_args(n, dx_part_, *d_x);
  dx_reduce_.launch({cl::round_up(size_t(n), 64)}, {64});
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
  blend_.launch({cl::round_up(size_t(blend_entries_), 64)}, {64});
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
    zero_.launch({cl::round_up(n_params_, 64)}, {64});
  }
  if (n == 0) return;
  const bool dx = d_x != nullptr;
  if (dx) ensure_dx_part(n);
  blend(params, offset, t);  // the table the forward read
  bwd1_.set_args(n, blended_, 0u, x, x, scale_, meta_, pmeta1_, d_enc, stride, col, g_blended_,
                 0u, 0, dx ? 1 : 0, dx ? dx_part_ : scale_);
  bwd1_.launch({size_t(cfg_.levels)}, {1});
  spread_.set_args(blend_entries_, t, pmeta_, bmeta_, g_blended_, grad, uint32_t(grad_offset));
  spread_.launch({cl::round_up(size_t(blend_entries_), 64)}, {64});
  if (!dx) return;
  dx_reduce_.set_args(n, dx_part_, *d_x);
  dx_reduce_.launch({cl::round_up(size_t(n), 64)}, {64});
}

void TimeHashGrid::launch_points(cl::Kernel& k, int n) {
  const size_t items = (size_t(n) + size_t(chunk_) - 1) / size_t(chunk_);
  if (chunk_ == 1)
    k.launch({cl::round_up(items, 64), size_t(cfg_.levels)}, {64, 1});
  else
    k.launch({items, size_t(cfg_.levels)}, {1, 1});
}

}  // namespace sgnlf::field
