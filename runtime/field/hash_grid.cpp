// HashGrid host launcher: level table, parameter init, and the enqueueing of the kernels in
// kernels/field/hashgrid.cl.
#include "field/hash_grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "cl/launch.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf::field {
namespace {
constexpr int kChunk = 256;  // points per work-item of schedule "chunked" on a per-point profile
}  // namespace

std::vector<HashGridLevel> hash_grid_levels(const HashGridConfig& cfg) {
  cfg.validate();
  const uint64_t table = uint64_t(1) << cfg.log2_table_size;
  std::vector<HashGridLevel> out;
  uint64_t offset = 0;
  for (int l = 0; l < cfg.levels; ++l) {
    HashGridLevel lv{};
    lv.scale = float(double(cfg.base_resolution) * std::pow(double(cfg.per_level_scale), l) - 1.0);
    lv.res = uint32_t(std::ceil(double(lv.scale))) + 2u;
    const uint64_t dense = uint64_t(lv.res) * lv.res * lv.res;
    lv.size = uint32_t(std::min(table, (dense + 7) / 8 * 8));
    lv.hashed = dense > table ? 1u : 0u;
    lv.offset = uint32_t(offset);
    offset += lv.size;
    out.push_back(lv);
  }
  if (offset * uint64_t(cfg.features) >= (uint64_t(1) << 32))
    throw ConfigError("hash_grid: parameter count exceeds 2^32 floats");
  return out;
}

std::vector<float> barf_level_weights(double progress, int levels) {
  const double a = std::clamp(progress / 0.8 * levels, 0.0, double(levels));
  std::vector<float> w(size_t(std::max(levels, 0)));
  for (int k = 0; k < levels; ++k) {
    const double t = std::clamp(a - k, 0.0, 1.0);
    w[size_t(k)] = float((1.0 - std::cos(M_PI * t)) / 2.0);
  }
  return w;
}

HashGrid::HashGrid(cl::Runtime& rt, const HashGridConfig& cfg)
    : rt_(rt), cfg_(cfg), levels_(hash_grid_levels(cfg)) {
  n_params_ = size_t(levels_.back().offset + levels_.back().size) * size_t(cfg_.features);
  std::vector<float> scale;
  std::vector<uint32_t> meta;
  for (const auto& lv : levels_) {
    scale.push_back(lv.scale);
    meta.insert(meta.end(), {lv.res, lv.offset, lv.size, lv.hashed});
  }
  scale_ = cl::Buffer::from(rt_, scale);
  meta_ = cl::Buffer::from(rt_, meta);
  weights_ = cl::Buffer(rt_, sizeof(float) * size_t(cfg_.levels));
  set_level_weights(std::vector<float>(size_t(cfg_.levels), 1.0f));
  const std::string opt = "-DLEVELS=" + std::to_string(cfg_.levels) +
                          " -DFEATURES=" + std::to_string(cfg_.features);
  // Schedule "auto" takes the device profile's chunk (256 on CPUs, 1 = per point on GPUs).
  const int profile_chunk = rt_.device_profile().hash_grid_chunk;
  chunked_ = cfg_.schedule == "chunked" || (cfg_.schedule == "auto" && profile_chunk > 1);
  chunk_ = profile_chunk > 1 ? profile_chunk : kChunk;
  const std::string table_opt = opt + " -DHALF_TABLE=" + (cfg_.half_table ? "1" : "0") +
                                " -DCHUNK=" + std::to_string(chunk_);
  const std::string file = "field/hashgrid.cl";
  const std::string sfx = chunked_ ? "_chunk" : "";
  variant_ = cfg_.deterministic ? rt_.device_profile().encoder_backward
                                : cl::EncoderBackward::Atomic;
  fwd_ = rt_.kernel(file, "field_hashgrid_fwd" + sfx, table_opt);
  bwd_ = rt_.kernel(file, "field_hashgrid_bwd", opt);
  bwd_atomic_ = rt_.kernel(file, "field_hashgrid_bwd_atomic", opt);
  bwd_pairs_ = rt_.kernel(file, "field_hashgrid_bwd_pairs", opt);
  bwd_dx_ = rt_.kernel(file, "field_hashgrid_bwd_dx" + sfx, table_opt);
  dx_reduce_ = rt_.kernel(file, "field_hashgrid_dx_reduce", opt);
  zero_ = rt_.kernel(file, "field_hashgrid_zero", opt);
  if (cfg_.half_table) {
    to_half_ = rt_.kernel(file, "field_hashgrid_to_half", opt);
    half_ = cl::Buffer(rt_, n_params_ * 2);
  }
}

void HashGrid::init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) const {
  if (offset + n_params_ > host_params.size())
    throw Error("HashGrid::init_params: slice [" + std::to_string(offset) + ", +" +
                std::to_string(n_params_) + ") exceeds buffer of " +
                std::to_string(host_params.size()));
  Rng rng(seed, 0x4a5u);
  for (size_t i = 0; i < n_params_; ++i) host_params[offset + i] = rng.uniform(-1e-4f, 1e-4f);
}

void HashGrid::set_level_weights(const std::vector<float>& w) {
  if (w.size() != size_t(cfg_.levels))
    throw Error("HashGrid::set_level_weights: got " + std::to_string(w.size()) +
                " weights for " + std::to_string(cfg_.levels) + " levels");
  weights_host_ = w;
  up_weights_.write_vec(weights_, w);  // non-blocking (BARF's weights change between steps)
}

static void check_bytes(const cl::Buffer& b, size_t floats, const char* what) {
  if (b.bytes() < floats * sizeof(float))
    throw Error(std::string("HashGrid: buffer '") + what + "' has " + std::to_string(b.bytes()) +
                " bytes, needs " + std::to_string(floats * sizeof(float)));
}

void HashGrid::forward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
                       cl::Buffer& enc) {
  if (n <= 0) return;
  check_bytes(params, offset + n_params_, "params");
  check_bytes(x, size_t(n) * 3, "x");
  check_bytes(enc, size_t(n) * size_t(n_output()), "enc");
  if (cfg_.half_table) {
    refresh_half(params, offset);
    fwd_.set_args(n, half_, uint32_t(0), x, scale_, meta_, weights_, enc);
  } else {
    fwd_.set_args(n, params, uint32_t(offset), x, scale_, meta_, weights_, enc);
  }
  launch_levels(fwd_, n);
}

void HashGrid::backward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
                        const cl::Buffer& d_enc, cl::Buffer& grad, size_t grad_offset,
                        cl::Buffer* d_x) {
  check_bytes(grad, grad_offset + n_params_, "grad");
  check_bytes(x, size_t(std::max(n, 0)) * 3, "x");
  check_bytes(d_enc, size_t(std::max(n, 0)) * size_t(n_output()), "d_enc");
  if (variant_ == cl::EncoderBackward::Serial || n <= 0) {
    bwd_.set_args(std::max(n, 0), x, scale_, meta_, weights_, d_enc, grad, uint32_t(grad_offset));
    bwd_.launch({size_t(cfg_.levels)}, {1});
  } else if (variant_ == cl::EncoderBackward::Atomic) {
    zero_.set_args(grad, uint32_t(grad_offset), uint32_t(n_params_));
    cl::launch_1d(zero_, n_params_);
    bwd_atomic_.set_args(n, x, scale_, meta_, weights_, d_enc, grad, uint32_t(grad_offset));
    cl::launch_rows(bwd_atomic_, size_t(n), size_t(cfg_.levels));
  } else {
    if (!reduction_) {
      std::vector<EntryRange> ranges;
      for (int l = 0; l < cfg_.levels; ++l)
        ranges.push_back({uint32_t(l), levels_[size_t(l)].offset, levels_[size_t(l)].size});
      reduction_ = std::make_unique<EntryReduction>(rt_, cfg_.features, cfg_.levels, 8, 8,
                                                    std::move(ranges));
    }
    reduction_->reserve(n);
    bwd_pairs_.set_args(n, x, scale_, meta_, weights_, d_enc, reduction_->keys(),
                        reduction_->vals(), reduction_->coef(), reduction_->vec());
    cl::launch_rows(bwd_pairs_, size_t(n), size_t(cfg_.levels));
    reduction_->reduce(n, grad, grad_offset, false);
  }
  if (d_x && n > 0) {
    check_bytes(params, offset + n_params_, "params");
    check_bytes(*d_x, size_t(n) * 3, "d_x");
    if (dx_part_points_ < size_t(n)) {
      dx_part_ = cl::Buffer(rt_, size_t(n) * size_t(cfg_.levels) * 3 * sizeof(float));
      dx_part_points_ = size_t(n);
    }
    if (cfg_.half_table) {
      refresh_half(params, offset);
      bwd_dx_.set_args(n, half_, uint32_t(0), x, scale_, meta_, weights_, d_enc, dx_part_);
    } else {
      bwd_dx_.set_args(n, params, uint32_t(offset), x, scale_, meta_, weights_, d_enc, dx_part_);
    }
    launch_levels(bwd_dx_, n);
    dx_reduce_.set_args(n, dx_part_, *d_x);
    cl::launch_1d(dx_reduce_, size_t(n));
  }
}

void HashGrid::launch_levels(cl::Kernel& k, int n) {
  if (chunked_)
    k.launch({(size_t(n) + size_t(chunk_) - 1) / size_t(chunk_), size_t(cfg_.levels)}, {1, 1});
  else
    cl::launch_rows(k, size_t(n), size_t(cfg_.levels));
}

void HashGrid::refresh_half(const cl::Buffer& params, size_t offset) {
  if (!half_dirty_ && half_src_ == params.get() && half_src_offset_ == offset) return;
  to_half_.set_args(params, uint32_t(offset), uint32_t(n_params_), half_);
  cl::launch_1d(to_half_, n_params_);
  half_dirty_ = false;
  half_src_ = params.get();
  half_src_offset_ = offset;
}

}  // namespace sgnlf::field
