// Multi-resolution hash-grid encoding (method.md §0; instant-ngp) on OpenCL: forward, parameter
// backward (race-free and deterministic by default) and input-position backward d_x, which is
// how ray origins/directions and hence poses receive gradients.
//
// Layout of this module's parameter slice: levels one after another; level l has `size` entries
// of F floats (entry-major). Level l: scale_l = base · growth^l − 1, res_l = ceil(scale_l) + 2,
// size_l = min(2^log2_table_size, round_up(res_l³, 8)); levels with res_l³ > table size use the
// spatial hash (x ⊕ y·2654435761 ⊕ z·805459861), the others a dense index (coordinates clamped
// to [0, res − 1], which only matters outside the unit box). Inputs x are N×3
// in [−1, 1]; pos = ((x + 1)/2)·scale_l + 0.5; trilinear over the 8 corners.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cl/runtime.hpp"
#include "cl/staged_upload.hpp"
#include "core/config_fwd.hpp"
#include "field/entry_reduction.hpp"
#include "field/hash_grid_config.hpp"

namespace sgnlf::field {

struct HashGridLevel {
  float scale;    // grid scale (base · growth^l − 1)
  uint32_t res;   // grid points per axis
  uint32_t offset;  // first entry of the level within the module slice
  uint32_t size;  // entries
  uint32_t hashed;  // 1 = spatial hash, 0 = dense index
};

// The per-level table of a configuration (pure host function, shared with tests).
std::vector<HashGridLevel> hash_grid_levels(const HashGridConfig& cfg);

// BARF coarse-to-fine level weights (method.md §3): a = clamp(progress/0.8 · L, 0, L);
// w_k = (1 − cos(π · clamp(a − k, 0, 1))) / 2.
std::vector<float> barf_level_weights(double progress, int levels);

// The parameter backward: with `deterministic` (every preset) the device profile's
// encoder_backward (serial on CPUs, the deterministic parallel one on GPUs, bit-identical to
// each other), else the atomic kernel; set_backward() overrides it (tests, benchmarks).
class HashGrid {
 public:
  HashGrid(cl::Runtime& rt, const HashGridConfig& cfg);

  const HashGridConfig& config() const { return cfg_; }
  cl::EncoderBackward backward_variant() const { return variant_; }
  void set_backward(cl::EncoderBackward v) { variant_ = v; }
  // Points per work-item of the forward and d_x (1 = the per-point kernels).
  int chunk() const { return chunked_ ? chunk_ : 1; }
  const std::vector<HashGridLevel>& levels() const { return levels_; }
  size_t n_params() const { return n_params_; }
  int n_output() const { return cfg_.levels * cfg_.features; }

  // Uniform ±1e-4 (instant-ngp) into host_params[offset, offset + n_params()) from `seed`.
  void init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) const;

  // Level weights (L floats, 1 = on) used by forward and backward until changed. Blocking
  // upload: call between training steps. Default: all ones.
  void set_level_weights(const std::vector<float>& w);
  const std::vector<float>& level_weights() const { return weights_host_; }

  // With half_table: the fp32 parameters changed (e.g. after an Adam step); the next forward
  // refreshes the fp16 copy. Also refreshed when forward sees another buffer or offset.
  void params_changed() { half_dirty_ = true; }

  // enc (N × L·F floats) = encoding of x (N × 3 floats). Enqueued, no wait.
  void forward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
               cl::Buffer& enc);
  // Overwrites grad[grad_offset, + n_params()) with dL/dparams; if d_x is given, writes
  // dL/dx (N × 3). Enqueued, no wait.
  void backward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
                const cl::Buffer& d_enc, cl::Buffer& grad, size_t grad_offset,
                cl::Buffer* d_x = nullptr);

 private:
  cl::Runtime& rt_;
  HashGridConfig cfg_;
  std::vector<HashGridLevel> levels_;
  size_t n_params_ = 0;
  std::vector<float> weights_host_;
  cl::Buffer scale_, meta_, weights_;
  cl::StagedUpload up_weights_;  // the level weights, written without blocking
  cl::Kernel fwd_, bwd_, bwd_atomic_, bwd_pairs_, bwd_dx_, dx_reduce_, zero_, to_half_;
  cl::EncoderBackward variant_ = cl::EncoderBackward::Serial;
  std::unique_ptr<EntryReduction> reduction_;  // made on the first deterministic parallel pass
  cl::Buffer dx_part_;  // L × N × 3 per-level d_x contributions
  size_t dx_part_points_ = 0;
  cl::Buffer half_;  // fp16 table when half_table
  bool chunked_ = false;
  int chunk_ = 256;
  bool half_dirty_ = true;
  cl_mem half_src_ = nullptr;
  size_t half_src_offset_ = 0;
  void refresh_half(const cl::Buffer& params, size_t offset);
  void launch_levels(cl::Kernel& k, int n);
};

}  // namespace sgnlf::field
