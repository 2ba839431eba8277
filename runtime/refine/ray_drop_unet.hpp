// LiDAR4D's ray-drop refinement U-Net (method.md §2; LiDAR4D's model/unet.py, CVPR 2024) on
// the conv stack (runtime/conv), with its parameters in one flat buffer (field::ParamLayout,
// slices "unet.<layer>") that one field::Adam updates, as the PatchGAN discriminator does.
//
//   x (n × h × w × 3: return probability, intensity, depth / depth_scale_m)
//   e0 = act(conv1×1(x))                                   "1×1 in", `channels`
//   e_l = act(conv3(act(conv3(maxpool2(e_{l−1})))))        l = 1 … depth (down stages)
//   d_depth = e_depth
//   d_l = act(conv3(act(conv3([e_l, up2(d_{l+1})]))))      l = depth − 1 … 0 (up stages, skips)
//   logit = conv1×1(d0), p = σ(logit)
// Widths: e_l has channels·2^min(l, depth − 1); the up stage at level l keeps its
// concatenation's width in its first conv and ends with the width of e_{max(l − 1, 0)}. up2 is
// bilinear ×2 (align_corners), zero-padded to e_l's size. act is (leaky) ReLU.
//
// Left out from LiDAR4D's network (said in method deviations): BatchNorm (the conv stack has
// none; the convs keep their biases instead), Dropout2d(0.1), and the bottleneck multi-head
// self-attention block (AttnBlock); LiDAR4D's pre-activation order (BN → ReLU → conv) becomes
// conv → act, which without BatchNorm differs only in that up2 interpolates activated features.
// Without BatchNorm and dropout the network has no training mode: the forward is one
// deterministic function of parameters and input (inference is what evaluation runs; LiDAR4D's
// released refine() leaves its U-Net in training mode).
//
// Everything is enqueued without waiting except loss() and the read functions. Deterministic:
// no atomics, fixed reduction orders, so equal seeds and inputs give bit-identical parameters.
#pragma once
#include <memory>
#include <vector>

#include "cl/runtime.hpp"
#include "conv/bce_loss.hpp"
#include "conv/box_mask.hpp"
#include "conv/channel_copy.hpp"
#include "conv/conv2d.hpp"
#include "conv/leaky_relu.hpp"
#include "conv/max_pool.hpp"
#include "conv/upsample.hpp"
#include "field/adam.hpp"
#include "field/param_layout.hpp"
#include "refine/ray_drop_unet_config.hpp"

namespace sgnlf::refine {

class RayDropUNet {
 public:
  static constexpr int kInputChannels = 3;  // return probability, intensity, depth (metres)

  RayDropUNet(cl::Runtime& rt, const RayDropUNetConfig& cfg);
  RayDropUNet(const RayDropUNet&) = delete;
  RayDropUNet& operator=(const RayDropUNet&) = delete;

  cl::Runtime& runtime() { return rt_; }
  const RayDropUNetConfig& config() const { return cfg_; }
  const field::ParamLayout& layout() const { return layout_; }
  size_t n_params() const { return layout_.total(); }
  cl::Buffer& params() { return params_; }
  const cl::Buffer& grad() const { return grad_; }
  // The initial parameters (from cfg.seed), as uploaded by the constructor.
  std::vector<float> initial_params() const;
  // Re-uploads initial_params() and resets Adam (blocking).
  void reset();

  // Width of e_l (l = 0 … depth).
  int width(int level) const { return widths_[size_t(level)]; }
  // Throws Error when h × w cannot be pooled `depth` times (each side >= 2^depth).
  void check_size(int h, int w) const;
  // Multiply-adds of one forward pass over n images of h × w (convolutions only).
  double forward_macs(int n, int h, int w) const;

  // Inference: probs (n × h × w, compact) = σ(U-Net(inputs)); inputs n × h × w × 3 as above
  // (depth in metres). No augmentation. Enqueued.
  void forward(const cl::Buffer& inputs, int n, int h, int w, cl::Buffer& probs);
  // Mean BCE of the inference output against masks (n × h × w, 1 = return) (blocking).
  double loss(const cl::Buffer& inputs, const cl::Buffer& masks, int n, int h, int w);
  // One training step: pack the inputs with boxes [box_off, box_off + n_boxes) of `boxes`
  // (int quadruples y0, x0, y1, x1) zeroed, forward, mean BCE against masks into
  // losses[slot], backward into grad(), Adam with learning rate lr. Enqueued.
  void step(const cl::Buffer& inputs, const cl::Buffer& masks, int n, int h, int w,
            const cl::Buffer& boxes, int box_off, int n_boxes, float lr, cl::Buffer& losses,
            int slot);

 private:
  struct Block {  // two 3×3 convs with activations
    std::unique_ptr<conv::Conv2d> a, b;
    size_t off_a = 0, off_b = 0;
    cl::Buffer pre_a, post_a, pre_b, post_b;
  };
  struct Level {
    int h = 0, w = 0;
    cl::Buffer pooled;  // maxpool2(e_{l−1}) (l >= 1)
    cl::Buffer cat;     // [e_l, up2(d_{l+1})] (l < depth)
    cl::Buffer g_e;     // gradient of e_l
  };
  void ensure(int n, int h, int w);
  const cl::Buffer& e(int l) const;  // e_l (post-activation)
  const cl::Buffer& d(int l) const;  // d_l (post-activation; e_depth for l = depth)
  int up_width(int l) const;         // width of d_{l+1}
  int dec_width(int l) const;        // width of d_l
  void pack(const cl::Buffer& inputs, int n, const cl::Buffer& boxes, int box_off, int n_boxes);
  void run_forward(int n);
  void run_backward(int n);
  void block_forward(Block& b, const cl::Buffer& in, int n, int h, int w);
  // dy: gradient of b's output (overwritten: through the activation in place); d_in: of b's
  // input. Parameter gradients into grad_.
  void block_backward(Block& b, const cl::Buffer& in, int n, int h, int w, cl::Buffer& dy,
                      cl::Buffer& d_in);

  cl::Runtime& rt_;
  RayDropUNetConfig cfg_;
  std::vector<int> widths_;
  field::ParamLayout layout_;
  std::unique_ptr<conv::Conv2d> inc_, outc_;
  size_t off_in_ = 0, off_out_ = 0;
  std::vector<Block> enc_, dec_;  // enc_[l] for l = 1 … depth (enc_[0] unused), dec_[l] l < depth
  conv::LeakyRelu act_;
  conv::MaxPool2x2 pool_;
  conv::Upsample2x up_;
  conv::ChannelCopy copy_;
  conv::BceWithLogits bce_;
  conv::BoxMask mask_;
  std::unique_ptr<field::Adam> adam_;
  cl::Buffer params_, grad_, scale_, no_boxes_, eval_loss_;
  cl::Buffer x_, e0_pre_, e0_post_, logits_, d_logits_, scratch_[3];
  std::vector<Level> levels_;
  int cap_ = 0, h_ = 0, w_ = 0;
};

}  // namespace sgnlf::refine
