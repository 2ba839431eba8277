// Time-sliced 2D hash grids (method.md §2, LiDAR4D's dynamic hash encoding) on OpenCL: forward,
// deterministic parameter backward and input-position backward d_x
// (kernels/field/hashgrid_time.cl).
//
// Three planes xy, xz, yz; each is a stack of `time_slices` 2D multi-resolution hash grids of
// the same shape (one per time slice). A time t ∈ [0, 1] lies at u = t·(T − 1) between slices
// floor(u) and floor(u) + 1 and blends their features linearly (LiDAR4D's HashGridT); per level
// the three planes' blended features are multiplied (Hadamard), giving L·F columns like the 3D
// hash grid (hash_grid.hpp) whose conventions it shares: level l's scale base·growth^l − 1,
// res = ceil(scale) + 2, pos = ((x + 1)/2)·scale + 0.5, a dense index where res² fits the table,
// else the spatial hash gx ⊕ gy·2654435761. LiDAR4D's sizes: 8 levels × 4 features, base 512,
// finest 32768, tables 2^14 (xy), 2^12 (xz, yz); its time resolution (25 there) is one number
// shared with the planes, T = 8 here (the spec's time resolution).
// Layout of the module slice: plane p at plane.offset entries, then its slices one after
// another (slice_entries each), in each slice the levels one after another, F floats per entry.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cl/runtime.hpp"
#include "core/config_fwd.hpp"
#include "field/entry_reduction.hpp"
#include "field/hash_grid.hpp"
#include "field/time_hash_grid_config.hpp"

namespace sgnlf::field {

struct TimeHashPlane {
  uint32_t offset = 0;         // first entry of the plane within the module slice
  uint32_t slice_entries = 0;  // entries of one time slice (all levels)
  std::vector<HashGridLevel> levels;  // offsets within a slice
};

// The three planes' tables of a configuration (pure host function, shared with tests).
std::vector<TimeHashPlane> time_hash_grid_planes(const TimeHashGridConfig& cfg);

class TimeHashGrid {
 public:
  TimeHashGrid(cl::Runtime& rt, const TimeHashGridConfig& cfg);

  const TimeHashGridConfig& config() const { return cfg_; }
  // The parameter backward: the device profile's encoder_backward (serial on CPUs, the
  // deterministic parallel one, bit-identical to it, on GPUs); set_backward() overrides it.
  cl::EncoderBackward backward_variant() const { return variant_; }
  void set_backward(cl::EncoderBackward v) { variant_ = v; }
  const std::vector<TimeHashPlane>& planes() const { return planes_; }
  size_t n_params() const { return n_params_; }
  int n_output() const { return cfg_.levels * cfg_.features; }

  // Uniform ±1e-4 (instant-ngp, tiny-cuda-nn's default) into host_params[offset, + n_params()).
  void init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) const;

  // enc[i·stride + col + c], c < n_output(): encoding of x (N × 3) at times t (N).
  // stride 0 = n_output(). Enqueued, no wait.
  void forward(const cl::Buffer& params, size_t offset, const cl::Buffer& x,
               const cl::Buffer& t, int n, cl::Buffer& enc, int stride = 0, int col = 0);
  // Overwrites grad[grad_offset, + n_params()) with dL/dparams (adds to it with accumulate);
  // if d_x is given, overwrites it with dL/dx (N × 3; time is not differentiated).
  void backward(const cl::Buffer& params, size_t offset, const cl::Buffer& x,
                const cl::Buffer& t, int n, const cl::Buffer& d_enc, cl::Buffer& grad,
                size_t grad_offset, cl::Buffer* d_x = nullptr, bool accumulate = false,
                int stride = 0, int col = 0);

  // The same at one time t for every point (LiDAR4D's ray batches are one frame each; t is
  // clamped to [0, 1], a non-finite t is refused): the two neighbouring slices are blended once
  // into a one-slice table that the points read (4 corner reads per plane instead of 8), and
  // the backward spreads that table's gradient back onto the two slices.
  void forward_at(const cl::Buffer& params, size_t offset, const cl::Buffer& x, float t, int n,
                  cl::Buffer& enc, int stride = 0, int col = 0);
  void backward_at(const cl::Buffer& params, size_t offset, const cl::Buffer& x, float t, int n,
                   const cl::Buffer& d_enc, cl::Buffer& grad, size_t grad_offset,
                   cl::Buffer* d_x = nullptr, bool accumulate = false, int stride = 0,
                   int col = 0);

 private:
  cl::Runtime& rt_;
  TimeHashGridConfig cfg_;
  std::vector<TimeHashPlane> planes_;
  size_t n_params_ = 0;
  int chunk_ = 1;
  cl::Buffer scale_, meta_, pmeta_;
  cl::Kernel fwd_, bwd_, dx_reduce_;
  // The parallel backwards (device profile's encoder_backward): per (point, level), atomic or
  // pairs for the EntryReduction, of the full table and of the one-slice table.
  cl::EncoderBackward variant_ = cl::EncoderBackward::Serial;
  cl::Kernel bwd_points_, bwd_points1_;
  std::unique_ptr<EntryReduction> reduction_, reduction1_;  // made on first use
  // One time for all points: the blend and spread kernels, the one-slice build of the forward
  // and backward (-DSLICES=1), the planes' entries in the one-slice table (bmeta_: first entry
  // of each plane; pmeta1_: as pmeta_ for that table), the table and its gradient.
  cl::Kernel blend_, spread_, zero_, fwd1_, bwd1_;
  cl::Buffer bmeta_, pmeta1_, blended_, g_blended_;
  int blend_entries_ = 0;
  cl::Buffer dx_part_;
  size_t dx_part_floats_ = 0;
  void check(const cl::Buffer& params, size_t offset, const cl::Buffer& x, const cl::Buffer* t,
             int n, const cl::Buffer& enc, int stride, int col, const char* what) const;
  void ensure_dx_part(int n);
  void blend(const cl::Buffer& params, size_t offset, float t);
  void launch_points(cl::Kernel& k, int n);
  EntryReduction& reduction(bool one_slice);
};

}  // namespace sgnlf::field
