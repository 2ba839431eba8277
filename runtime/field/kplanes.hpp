// K-Planes-style 4D plane encoding (method.md §2, LiDAR4D's planes; K-Planes, Fridovich-Keil
// et al. 2023) on OpenCL: forward, deterministic parameter backward and input-position
// backward d_x (kernels/field/kplanes.cl).
//
// Per scale s (spatial resolution R_s = resolution · 2^s points per axis, time resolution T):
// six planes, static xy, xz, yz and dynamic xt, yt, zt, each F features per grid point,
// sampled bilinearly (align_corners, border padding) at x ∈ [−1, 1]³ and t ∈ [0, 1]. A group's
// feature at a scale is the Hadamard product of its three planes; the output concatenates the
// scales, static group first: [static s0..s(S−1) | dynamic s0..s(S−1)], S·F columns each.
// LiDAR4D feeds its planes coordinates in [0, 1] and so samples only half of each 64-point
// plane (about 32 cells across the box) and of its 25-point time axis; here the box spans the
// whole plane, with the spec's 32·{1, 2, 4, 8} points and T = 8.
// Layout of the module slice: scales one after another, in each the six planes in the order
// above, each W·H entries of F floats (entry (i, j) at i + j·W), no gaps.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cl/runtime.hpp"
#include "core/config_fwd.hpp"
#include "field/entry_reduction.hpp"
#include "field/kplanes_config.hpp"

namespace sgnlf::field {

// Which plane groups a pass computes: both (the point's own time), or one of them (LiDAR4D
// samples only the dynamic planes at the flowed neighbour positions).
enum class PlaneGroups { Both, Static, Dynamic };

struct KPlane {
  int scale = 0;
  int plane = 0;          // 0..5: xy, xz, yz, xt, yt, zt
  uint32_t offset = 0;    // first entry within the module slice
  uint32_t width = 0;     // grid points along the plane's first axis
  uint32_t height = 0;    // along its second axis
};

// The plane table of a configuration (pure host function, shared with tests).
std::vector<KPlane> kplanes_layout(const KPlanesConfig& cfg);

class KPlanes {
 public:
  KPlanes(cl::Runtime& rt, const KPlanesConfig& cfg);

  const KPlanesConfig& config() const { return cfg_; }
  // The parameter backward: the device profile's encoder_backward (serial on CPUs, the
  // deterministic parallel one, bit-identical to it, on GPUs); set_backward() overrides it.
  cl::EncoderBackward backward_variant() const { return variant_; }
  void set_backward(cl::EncoderBackward v) { variant_ = v; }
  const std::vector<KPlane>& planes() const { return planes_; }
  size_t n_params() const { return n_params_; }
  // Output columns of a pass over `groups` (S·F per group).
  int n_output(PlaneGroups groups = PlaneGroups::Both) const;

  // Spatial planes uniform in [init_lo, init_hi], time planes 1, into
  // host_params[offset, offset + n_params()) from `seed`.
  void init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) const;

  // enc[i·stride + col + c], c < n_output(groups): encoding of x (N × 3) at times t (N).
  // stride 0 = n_output(groups). Enqueued, no wait.
  void forward(const cl::Buffer& params, size_t offset, const cl::Buffer& x,
               const cl::Buffer& t, int n, cl::Buffer& enc,
               PlaneGroups groups = PlaneGroups::Both, int stride = 0, int col = 0);
  // From d_enc (same columns as forward): writes dL/dparams of the planes of `groups` into
  // grad[grad_offset + …] (overwriting them, or adding to them with accumulate; the other
  // group's planes are untouched); if d_x is given, overwrites it with dL/dx (N × 3; time is
  // not differentiated). Enqueued, no wait.
  void backward(const cl::Buffer& params, size_t offset, const cl::Buffer& x,
                const cl::Buffer& t, int n, const cl::Buffer& d_enc, cl::Buffer& grad,
                size_t grad_offset, cl::Buffer* d_x = nullptr,
                PlaneGroups groups = PlaneGroups::Both, bool accumulate = false, int stride = 0,
                int col = 0);

 private:
  cl::Runtime& rt_;
  KPlanesConfig cfg_;
  std::vector<KPlane> planes_;
  size_t n_params_ = 0;
  int chunk_ = 1;
  cl::Buffer meta_;
  cl::Kernel fwd_, bwd_, dx_reduce_, bwd_points_;
  cl::EncoderBackward variant_ = cl::EncoderBackward::Serial;
  // Per group selection (both, static, dynamic): the reduction over its planes, made on first use.
  std::unique_ptr<EntryReduction> reductions_[3];
  EntryReduction& reduction(PlaneGroups groups);
  cl::Buffer dx_part_;
  size_t dx_part_floats_ = 0;
  void check(const cl::Buffer& params, size_t offset, const cl::Buffer& x, const cl::Buffer& t,
             int n, const cl::Buffer& enc, int width, int stride, int col, const char* what) const;
  void launch_points(cl::Kernel& k, int n, int rows);
};

}  // namespace sgnlf::field
