// 2-D convolution on OpenCL (kernels/conv/conv2d.cl, conv2d_narrow.cl): forward, backward
// w.r.t. the input and w.r.t. weights and bias, zero padding, any stride, square kernels (4×4
// and 3×3 in use), batch N >= 1. Register-tiled implicit GEMMs; the weight gradient is a
// deterministic two-phase reduction (fixed chunking from the shapes alone, fixed summation
// order). Narrow shapes (c_out <= 2, c_in <= 4) use kernels vectorised over the other channels.
//
// Layout: NHWC with a channel stride, element (n, y, x, c) at ((n·H + y)·W + x)·cs + c. Chosen
// over NCHW because the output channels of a pixel are contiguous: the kernels accumulate 16
// output channels as one float16 vector and load each weight row once per tile of pixels
// (performance.md: explicit vectors are what PoCL turns into AVX-512; on a GPU it is the usual
// implicit-GEMM layout). The input may have any cs >= c_in (e.g. 2 for a [D_ij, D_j] image);
// the output has cs = out_cs() = round_up(c_out, 16) with zero padding channels, so layers
// chain without copies.
//
// Parameter slice (in one flat buffer, runtime/field/param_layout.hpp): W[(ky·k + kx)·c_in +
// c][out_cs] then bias[out_cs]; padding columns are zero and receive zero gradient.
//
// Kernels: the Runtime's device profile, read when the Conv2d is made, chooses them by its
// `gemm` key, as for the MLP. cpu_tiles: kernels/conv/conv2d.cl and conv2d_narrow.cl (float16
// register tiles, what every run used before profiles). local_tiles (the gpu profile's):
// kernels/conv/conv2d_tiles.cl, local-memory tiles with the profile's gemm_* tiles and register
// block (<= 32 floats per work-item), a 1 x 1 block with 16-column tiles for launches under
// gemm_min_work_items (the same sums, the same bits).
#pragma once
#include <cstdint>
#include <vector>

#include "cl/gemm_tiles.hpp"
#include "cl/runtime.hpp"

namespace sgnlf::conv {

struct Conv2dSpec {
  int c_in = 2;
  int c_out = 32;
  int kernel = 4;  // square kernel size
  int stride = 2;
  int pad = 1;     // zero padding on every side
  int in_cs = 0;   // channel stride of the input (0: round_up(c_in, 16) when c_in >= 16, else c_in)
  void validate() const;  // throws ConfigError naming the bad value
  int input_cs() const;
  int out_cs() const { return (c_out + 15) / 16 * 16; }
  int out_size(int in) const {  // 0 when the padded input is smaller than the kernel
    return in + 2 * pad < kernel ? 0 : (in + 2 * pad - kernel) / stride + 1;
  }
  size_t n_params() const { return (size_t(kernel) * kernel * c_in + 1) * size_t(out_cs()); }
  // Multiply-adds of a forward pass over n images of h × w (backward: 2×, input + weights).
  double macs(int n, int h, int w) const {
    return double(n) * out_size(h) * out_size(w) * kernel * kernel * c_in * c_out;
  }
  // Index of weight (ky, kx, c → o) and of bias o within the slice.
  size_t weight_index(int ky, int kx, int c, int o) const {
    return (size_t(ky * kernel + kx) * c_in + c) * out_cs() + o;
  }
  size_t bias_index(int o) const { return size_t(kernel) * kernel * c_in * out_cs() + o; }
};

class Conv2d {
 public:
  Conv2d(cl::Runtime& rt, const Conv2dSpec& spec);

  const Conv2dSpec& spec() const { return spec_; }
  size_t n_params() const { return spec_.n_params(); }

  // Weights N(0, stddev²) from the project's Philox generator (seed, stream "CV"), bias 0,
  // padding 0; writes host_params[offset, + n_params()).
  void init_params(std::vector<float>& host_params, size_t offset, uint64_t seed,
                   float stddev) const;

  // out (n × ho × wo × out_cs) = conv(in (n × h × w × input_cs)); with `act_out` also
  // act_out = leaky_relu(out, slope) in the same pass (out stays the pre-activation, which the
  // backward of the activation needs). Enqueued, no wait.
  void forward(const cl::Buffer& params, size_t offset, const cl::Buffer& in, int n, int h,
               int w, cl::Buffer& out, cl::Buffer* act_out = nullptr, float slope = 0.0f);
  // From d_out (the output's layout; its padding channels c_out.. must be zero, as the
  // adversarial hinge writes them and as they stay when c_out is a multiple of 16, since the
  // input backward writes only the c_in channels of d_in): overwrites grad[grad_offset,
  // + n_params()) when grad is
  // given and writes d_in (the input's layout, its c_in channels only) when given. `in` is the
  // forward's input. Enqueued, no wait.
  void backward(const cl::Buffer& params, size_t offset, const cl::Buffer& in, int n, int h,
                int w, const cl::Buffer& d_out, cl::Buffer* grad, size_t grad_offset,
                cl::Buffer* d_in);

  // True when the local_tiles kernels are used (device profile gemm = local_tiles).
  bool local_tiles() const { return tiles_; }
  // True when the narrow-output kernels are used (cpu_tiles, c_out <= 2, c_in and input_cs
  // % 16 == 0).
  bool narrow() const { return narrow_; }
  // True when the input backward vectorises over output channels (cpu_tiles, c_in <= 4).
  bool narrow_input() const { return narrow_in_; }
  // Chunks of the weight-gradient reduction for an output of `pixels` pixels (shapes and the
  // profile only: cpu_tiles chunks of >= 256 pixels, at most 256; local_tiles the profile's
  // gemm_chunk_points and gemm_max_chunks; both at most 16 MiB of partial sums).
  int wgrad_chunks(int pixels) const;

 private:
  void check_shape(int n, int h, int w, const char* where) const;
  cl::Runtime& rt_;
  Conv2dSpec spec_;
  // Narrow outputs (c_out <= 2, c_in and the input's channel stride multiples of 16): forward
  // and weight gradient vectorised over input channels instead of output channels.
  bool narrow_ = false;
  bool narrow_in_ = false;  // c_in <= 4: input backward vectorised over output channels
  cl::Kernel fwd_, transpose_, bwd_in_, bwd_wgt_, reduce_;
  bool tiles_ = false;
  cl::DeviceProfile profile_;
  // local_tiles: the GEMM kernels of the profile's register block and of the 1 x 1 block
  // (cl/gemm_tiles.hpp), and the chunk partials' fixed tree (block-independent).
  cl::GemmKernels gemm_;
  cl::Kernel reduce_tiles_;
  cl::Buffer zeros_, wt_, partial_;
  size_t partial_floats_ = 0;
};

}  // namespace sgnlf::conv
