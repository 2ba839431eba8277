// Small fully connected networks on OpenCL (method.md §0: density MLP, LiDAR head; §4.1: Ψ).
// Per-layer activations {none, relu, tanh, softplus, sine}, widths up to 128 (padded internally
// to multiples of 16). forward() keeps what backward() needs in an MlpContext (tiny-cuda-nn
// style); backward() overwrites this module's slice of the gradient buffer with dL/dparams
// (deterministic: fixed chunking and summation order) and optionally writes dL/dinput.
//
// Parameter slice layout, per layer l with n_in inputs and out outputs (out_pad =
// round_up(out, 16)): W_t[n_in][out_pad] (W_t[i][o] = weight from input i to output o) followed
// by b[out_pad]; padding columns are zero and receive zero gradient.
//
// Grouped inputs (spec.n_in_group > 0): the network's input is [x_p, y_g], x_p per point
// (n_in values) and y_g shared by a group of `group` consecutive points (n_in_group values; the
// LiDAR head's direction encoding is the same for every sample of a ray). Layer 0 keeps the
// layout of an MLP with n_in + n_in_group inputs (rows of x, then rows of y, then the bias) and
// computes the same function, but the y part once per group: y_g · W_y + b, added to every
// point's x_p · W_x. Its backward sums the pre-activation gradient over each group first.
// Groups of varying size (GroupIndex): group g holds the consecutive points [offsets[g],
// offsets[g + 1]) and point_group[k] names each point's group (e.g. the live samples of each
// ray after early ray termination; a group may be empty).
// The per-point input may be a column range of a wider row (in_stride, in_offset); d_in is then
// written into the same columns of a buffer with that layout, other columns untouched.
//
// Towers (spec.towers = T > 1): T separate networks of 1/T the width side by side in one Mlp
// (LiDAR4D's intensity and ray-drop MLPs on the same input: one N × T output). Every layer's
// width is divisible by T. Layer 0 is dense (all inputs, grouped ones included, feed every
// unit); its output o belongs to tower o / (width / T). In every later layer W_t[i][o] exists
// only where input i's tower i / (n_in / T) equals output o's tower o / (out / T); the other
// weights are structurally zero: init_params writes 0 there and backward() gives them exactly
// zero gradient (so Adam keeps them at 0). Biases are free. Forward and d_in need nothing
// else (zero weights contribute exactly 0), so the Mlp computes the T separate networks; the
// kernels skip the zero blocks where a 16-wide tile lies within one tower (kernels/field/
// mlp.cl, TOWER_IN / TOWER_OUT), with the same results. macs_per_point() counts the products
// of the T networks (not the structural zeros).
//
// Kernels: the Runtime's device profile, read when the Mlp is made, chooses them
// (cl::DeviceProfile::gemm). cpu_tiles: kernels/field/mlp.cl, float16 register tiles (8 points
// x 16 outputs per work-item, the weight gradient in at most 256 chunks of at least 512 points
// summed in chunk order): what every run used before profiles. local_tiles: kernels/field/
// mlp_tiles.cl, local-memory tiles and a register block of gemm_block_rows x gemm_block_cols
// floats per work-item, no transpose kernel, the weight gradient in the profile's chunks summed
// in a fixed tree; a launch that would have fewer than gemm_min_work_items work-items takes a
// 1 x 1 block (built on first use; every sum keeps its order, so the results are the same).
// Both keep every feature above; they agree to float rounding and each is deterministic.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cl/gemm_tiles.hpp"
#include "cl/runtime.hpp"
#include "core/config_fwd.hpp"
#include "field/activation.hpp"

namespace sgnlf::field {

struct MlpLayerSpec {
  int width = 64;
  Activation activation = Activation::Relu;
};

struct MlpSpec {
  int n_in = 32;
  int n_in_group = 0;  // inputs shared by groups of consecutive points (0: none)
  int in_stride = 0;   // row stride of the per-point input, in floats (0: n_in)
  int in_offset = 0;   // first column of the per-point input within its row
  std::vector<MlpLayerSpec> layers;  // hidden layers then the output layer
  // false: every layer is bias-free (LiDAR4D's flow MLP): the bias rows stay in the layout,
  // are never read, keep their zero init and always receive a zero gradient.
  bool bias = true;
  int towers = 1;  // block-diagonal separate sub-networks after layer 0 (see above), 1..8
  void validate() const;  // throws ConfigError
  int n_out() const { return layers.empty() ? 0 : layers.back().width; }
  // Multiply-adds per point of a forward pass (×2 for FLOPs; backward ≈ 2× forward); with
  // grouped inputs the per-group part is macs_per_group().
  double macs_per_point() const;
  double macs_per_group() const { return layers.empty() ? 0.0 : double(n_in_group) * layers[0].width; }
  int row_stride() const { return in_stride > 0 ? in_stride : n_in; }
};

// A spec with `hidden` layers of `width` and activation `act`, then a linear output layer.
MlpSpec make_mlp_spec(int n_in, int width, int hidden, int n_out, Activation act,
                      Activation out_act = Activation::None);

// Groups of varying size for grouped inputs: int32 device buffers, point_group (N entries) and
// offsets (n_groups + 1 entries, offsets[0] = 0, offsets[n_groups] = N, non-decreasing).
struct GroupIndex {
  const cl::Buffer* point_group = nullptr;
  const cl::Buffer* offsets = nullptr;
  int n_groups = 0;
};

// What forward keeps for backward. Buffers grow on demand and are reused across calls.
// The input buffer given to forward() must stay alive and unchanged until backward().
struct MlpContext {
  int n = 0;
  const cl::Buffer* in = nullptr;
  const cl::Buffer* group_in = nullptr;  // grouped inputs: the per-group input and group size
  int group = 0;
  GroupIndex index;                      // varying groups (index.offsets set), else `group`
  cl::Buffer group_pre;                  // y_g · W_y + b per group
  std::vector<cl::Buffer> post;  // hidden layer outputs, N × out_pad
  std::vector<cl::Buffer> pre;   // pre-activations where the derivative needs them
  size_t capacity = 0;           // points the buffers hold
};

class Mlp {
 public:
  Mlp(cl::Runtime& rt, const MlpSpec& spec);

  const MlpSpec& spec() const { return spec_; }
  size_t n_params() const { return n_params_; }
  // Offset of layer l's W_t within the module slice (bias follows at + n_in·out_pad).
  size_t layer_offset(int l) const { return layer_off_[size_t(l)]; }
  static int pad16(int w) { return (w + 15) / 16 * 16; }

  // Fan-in uniform init: relu layers U(±√(6/fan_in)) (He), others U(±√(3/fan_in)); bias 0.
  // With towers, a later layer's fan-in is a tower's (n_in / T) and off-tower weights are 0;
  // a value is drawn for every slot either way (layout-stable stream).
  void init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) const;

  // out (N × n_out) = MLP(in (N × row_stride)). With grouped inputs, group_in holds N / group
  // rows of n_in_group (N a multiple of group), or index->n_groups rows when `index` is given
  // (then `group` is ignored). Enqueued, no wait.
  void forward(const cl::Buffer& params, size_t offset, const cl::Buffer& in, int n,
               cl::Buffer& out, MlpContext& ctx, const cl::Buffer* group_in = nullptr,
               int group = 0, const GroupIndex* index = nullptr);
  // From d_out (N × n_out): overwrites grad[grad_offset, + n_params()); writes d_in (the
  // input's layout, its columns only) and d_group_in (one row of n_in_group per group) when given.
  // `out` is the forward output. Enqueued, no wait.
  void backward(const cl::Buffer& params, size_t offset, const MlpContext& ctx,
                const cl::Buffer& out, const cl::Buffer& d_out, cl::Buffer& grad,
                size_t grad_offset, cl::Buffer* d_in = nullptr,
                cl::Buffer* d_group_in = nullptr);

 private:
  struct Layer {
    int n_in, in_stride, out, out_pad, out_stride;
    int n_rows;  // parameter rows before the bias: n_in, + n_in_group for layer 0
    Activation act;
    bool store_pre;
    cl::Kernel fwd, bwd_out, wgt, reduce, transpose, bwd_in, group_sum;
    // local_tiles: the GEMM kernels of the profile's register block and of the 1 x 1 block
    // (cl/gemm_tiles.hpp; in place of fwd, bwd_in, wgt and transpose above): forward over
    // out_pad columns, d_in over pad16(n_in), the weight gradient over out_pad.
    cl::GemmKernels gemm;
  };
  bool local_tiles() const { return profile_.gemm == cl::GemmVariant::LocalTiles; }
  size_t chunks(size_t rows) const;  // weight-gradient chunks for `rows` points
  // Whether W_t[i][o] of layer l is a structurally zero off-tower weight (never the bias row).
  bool off_tower(size_t l, int i, int o) const;
  void ensure(MlpContext& ctx, int n) const;
  void ensure_scratch(int n);
  // The GEMM variant's kernels and launches (mlp_gemm.cpp). build_layer compiles a layer's
  // kernels, specialised by -D defines, and returns its program's (file, options).
  std::pair<std::string, std::string> build_layer(Layer& L, int in_off, int prev_act,
                                                  bool prev_pre, bool group_bias, bool towered);
  // One layer's forward, output-layer d_pre, input backward, weight gradient (from its input
  // and d_pre, into grad at w_off) and grouped sums, enqueued with the profile's variant.
  void launch_fwd(Layer& L, int n, const cl::Buffer& params, uint32_t w_off,
                  const cl::Buffer& src, cl::Buffer& dst, cl::Buffer& pre,
                  const cl::Buffer& gbias, int group, const cl::Buffer& gidx, int indexed);
  void launch_bwd_in(Layer& L, int n, const cl::Buffer& params, uint32_t w_off,
                     const cl::Buffer& d_pre, const cl::Buffer& prev, cl::Buffer& d_in);
  void weight_grad(Layer& L, const cl::Buffer& src, const cl::Buffer& d_pre, int rows,
                   cl::Buffer& grad, size_t w_off);
  void launch_bwd_out(Layer& L, int n, const cl::Buffer& d_out, const cl::Buffer& y,
                      cl::Buffer& d_pre);
  void launch_group_sum(Layer& L, int ng, int group, const cl::Buffer& d_pre,
                        cl::Buffer& d_group, const cl::Buffer& offsets, int indexed);

  cl::Runtime& rt_;
  cl::DeviceProfile profile_;  // the Runtime's when the Mlp was made
  MlpSpec spec_;
  size_t n_params_ = 0;
  std::vector<size_t> layer_off_;
  std::vector<Layer> layers_;
  Layer group_{};  // layer 0's grouped part: n_in_group inputs, linear, into group_pre
  cl::Buffer d_pre_[2], partial_, wt_, d_group_;
  size_t scratch_points_ = 0, partial_floats_ = 0;
  // Towers: 0/1 mask of the slice from layer 1 on (tower_count_ entries, at layer_offset(1));
  // backward() zeroes the gradient where it is 0. Unset with towers = 1 or a single layer.
  cl::Kernel tower_mask_;
  cl::Buffer tower_keep_;
  size_t tower_count_ = 0;
};

}  // namespace sgnlf::field
