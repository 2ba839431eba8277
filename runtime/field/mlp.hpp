// Small fully connected networks on OpenCL (method.md §0: density MLP, LiDAR head; §4.1: Ψ).
// Per-layer activations {none, relu, tanh, softplus, sine}, widths up to 128 (padded internally
// to multiples of 16). forward() keeps what backward() needs in an MlpContext (tiny-cuda-nn
// style); backward() overwrites this module's slice of the gradient buffer with dL/dparams
// (deterministic: fixed chunking and summation order) and optionally writes dL/dinput.
//
// Parameter slice layout, per layer l with n_in inputs and out outputs (out_pad =
// round_up(out, 16)): W_t[n_in][out_pad] (W_t[i][o] = weight from input i to output o) followed
// by b[out_pad]; padding columns are zero and receive zero gradient.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "cl/runtime.hpp"
#include "core/config.hpp"

namespace sgnlf::field {

enum class Activation { None = 0, Relu = 1, Tanh = 2, Softplus = 3, Sine = 4 };
Activation activation_from_string(const std::string& s);  // "none", "relu", ...; throws
std::string to_string(Activation a);

struct MlpLayerSpec {
  int width = 64;
  Activation activation = Activation::Relu;
};

struct MlpSpec {
  int n_in = 32;
  std::vector<MlpLayerSpec> layers;  // hidden layers then the output layer
  void validate() const;  // throws ConfigError
  int n_out() const { return layers.empty() ? 0 : layers.back().width; }
  // Multiply-adds per point of a forward pass (×2 for FLOPs; backward ≈ 2× forward).
  double macs_per_point() const;
};

// A spec with `hidden` layers of `width` and activation `act`, then a linear output layer.
MlpSpec make_mlp_spec(int n_in, int width, int hidden, int n_out, Activation act,
                      Activation out_act = Activation::None);

// What forward keeps for backward. Buffers grow on demand and are reused across calls.
// The input buffer given to forward() must stay alive and unchanged until backward().
struct MlpContext {
  int n = 0;
  const cl::Buffer* in = nullptr;
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
  void init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) const;

  // out (N × n_out) = MLP(in (N × n_in)). Enqueued, no wait.
  void forward(const cl::Buffer& params, size_t offset, const cl::Buffer& in, int n,
               cl::Buffer& out, MlpContext& ctx);
  // From d_out (N × n_out): overwrites grad[grad_offset, + n_params()); writes d_in
  // (N × n_in) when given. `out` is the forward output. Enqueued, no wait.
  void backward(const cl::Buffer& params, size_t offset, const MlpContext& ctx,
                const cl::Buffer& out, const cl::Buffer& d_out, cl::Buffer& grad,
                size_t grad_offset, cl::Buffer* d_in = nullptr);

 private:
  struct Layer {
    int n_in, in_stride, out, out_pad, out_stride;
    Activation act;
    bool store_pre;
    cl::Kernel fwd, bwd_out, wgt, reduce, transpose, bwd_in;
  };
  void ensure(MlpContext& ctx, int n) const;
  void ensure_scratch(int n);

  cl::Runtime& rt_;
  MlpSpec spec_;
  size_t n_params_ = 0;
  std::vector<size_t> layer_off_;
  std::vector<Layer> layers_;
  cl::Buffer d_pre_[2], partial_, wt_;
  size_t scratch_points_ = 0, partial_floats_ = 0;
};

}  // namespace sgnlf::field
