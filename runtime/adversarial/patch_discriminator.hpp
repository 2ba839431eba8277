// Multi-scale PatchGAN discriminator for the adversarial cross-frame consistency (method.md
// §4.3), on the conv stack (runtime/conv). Per scale s (input average-pooled s times, 2×2):
// conv k×k (channels[0], strides[0]) → leaky ReLU → … → conv k×k stride 1 → one-channel patch
// logits. Each scale has its own weights (pix2pixHD's multi-scale discriminators), all in one
// flat parameter buffer (field::ParamLayout, slices "disc.s<scale>.conv<layer>") that the
// discriminator's own field::Adam updates.
//
// Inputs: pair images NHWC [n][h][w][2] in metres, channel 0 = D_ij (fake) or M_ij ⊙ D_j (real),
// channel 1 = D_j; 0 = no return. Depths are divided by depth_scale_m inside; gradients w.r.t.
// the inputs are returned per metre.
// Losses (method.md §4.3), each a mean over the patch logits of a scale, averaged over scales:
//   L_D   = mean max(0, 1 − D(real)) + mean max(0, 1 + D(fake))
//   L_con = −mean D(fake)
// A discriminator step runs real and fake as one batch of 2n images. Everything is enqueued
// without waiting; only read_*() block. Deterministic: no atomics, fixed reduction orders, so
// the same seed and inputs give bit-identical parameters on the same device.
#pragma once
#include <memory>
#include <vector>

#include "adversarial/patch_discriminator_config.hpp"
#include "cl/runtime.hpp"
#include "conv/avg_pool.hpp"
#include "conv/conv2d.hpp"
#include "conv/leaky_relu.hpp"
#include "field/adam.hpp"
#include "field/param_layout.hpp"

namespace sgnlf::adversarial {

struct HingeLosses {
  double d_real = 0;  // mean max(0, 1 − D(real)), averaged over scales
  double d_fake = 0;  // mean max(0, 1 + D(fake)), averaged over scales
  double d_total() const { return d_real + d_fake; }  // L_D
  double con = 0;     // L_con = −mean D(fake) of the last generator_grad()
};

class PatchDiscriminator {
 public:
  PatchDiscriminator(cl::Runtime& rt, const PatchDiscriminatorConfig& cfg);
  PatchDiscriminator(const PatchDiscriminator&) = delete;
  PatchDiscriminator& operator=(const PatchDiscriminator&) = delete;

  const PatchDiscriminatorConfig& config() const { return cfg_; }
  const field::ParamLayout& layout() const { return layout_; }
  size_t n_params() const { return layout_.total(); }
  cl::Buffer& params() { return params_; }
  const cl::Buffer& grad() const { return grad_; }
  field::Adam& adam() { return *adam_; }
  // The initial parameters (from cfg.seed), as uploaded by the constructor.
  std::vector<float> initial_params() const;
  // Re-uploads initial_params() and resets Adam (blocking).
  void reset();

  // Logit image size of `scale` for h × w inputs; throws Error naming the scale and layer when
  // the input is too small for the configured network.
  std::pair<int, int> logit_size(int scale, int h, int w) const;
  // Multiply-adds of one forward pass over n images of h × w (all scales, convolutions only).
  double forward_macs(int n, int h, int w) const;

  // Forward of n pair images (metres); the logits stay for read_logits(). Enqueued.
  void forward(const cl::Buffer& images_m, int n, int h, int w);
  // Logits of `scale` of the last forward (or step), n × lh × lw, row-major (blocking).
  std::vector<float> read_logits(int scale) const;

  // dL_D/dparams into grad() (overwrites), hinge losses kept for read_losses(); dL_D/d real and
  // /d fake (per metre, same layout as the inputs, overwritten) when given. Enqueued.
  void discriminator_grad(const cl::Buffer& real_m, const cl::Buffer& fake_m, int n, int h,
                          int w, cl::Buffer* d_real_m = nullptr, cl::Buffer* d_fake_m = nullptr);
  // One discriminator step: discriminator_grad() then Adam with cfg.lr. Enqueued.
  void step(const cl::Buffer& real_m, const cl::Buffer& fake_m, int n, int h, int w);
  // Generator term: L_con (kept for read_losses()) and dL_con/d fake per metre into d_fake_m
  // (overwritten), for the training loop to chain into the rendered depths. grad() and the
  // parameters are untouched. Enqueued.
  void generator_grad(const cl::Buffer& fake_m, int n, int h, int w, cl::Buffer& d_fake_m);
  // Losses of the last discriminator_grad()/step() and generator_grad() (blocking).
  HingeLosses read_losses() const;

 private:
  struct ScaleBuffers {
    int h = 0, w = 0;                 // input size of this scale
    std::vector<int> hs, ws;          // output size of each layer
    cl::Buffer x;                     // input (normalised), [cap][h][w][2]
    cl::Buffer dx;                    // its gradient
    std::vector<cl::Buffer> pre, post;  // hidden layers' conv outputs and activations
    cl::Buffer logits, d_logits, terms;
  };
  void ensure(int n_images, int h, int w);
  void pack(const cl::Buffer& src_m, int n, int dst_image);
  void run_forward(int nb);
  // Backward of the last forward of nb images: hinge terms (mode 0: first n_real images real;
  // 1: generator), parameter gradients when `param_grad`, input gradient into scales_[0].dx
  // when `input_grad`.
  void run_backward(int nb, int n_real, int mode, bool param_grad, bool input_grad);
  void unpack(int src_image, int n, cl::Buffer& dst_m);

  cl::Runtime& rt_;
  PatchDiscriminatorConfig cfg_;
  field::ParamLayout layout_;
  std::vector<std::unique_ptr<conv::Conv2d>> convs_;  // layers; shared by the scales
  std::vector<std::vector<size_t>> offsets_;          // [scale][layer] parameter offsets
  conv::LeakyRelu act_;
  conv::AvgPool2x2 pool_;
  cl::Buffer params_, grad_, losses_, scratch_[2];
  std::unique_ptr<field::Adam> adam_;
  cl::Kernel scale_k_, hinge_k_, sum_k_;
  std::vector<ScaleBuffers> scales_;
  int cap_ = 0, h_ = 0, w_ = 0, last_n_ = 0;
};

}  // namespace sgnlf::adversarial
