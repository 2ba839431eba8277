// Sigmoid + binary cross-entropy on one-channel logits (kernels/conv/bce.cl): the loss of
// LiDAR4D's ray-drop refinement (nn.BCELoss on the U-Net's sigmoid output, method.md §2), in
// the stable logit form ℓ = max(z, 0) − z·y + log(1 + exp(−|z|)), mean over the pixels, and
// dℓ̄/dz = (σ(z) − y) / count. Logits are channel 0 of a padded conv output (channel stride cs).
// The mean is a fixed-order two-phase sum (chunking from the count alone): deterministic.
#pragma once
#include "cl/runtime.hpp"

namespace sgnlf::conv {

class BceWithLogits {
 public:
  explicit BceWithLogits(cl::Runtime& rt);
  // Work-items of the first phase for `count` pixels (the shapes alone decide).
  static int chunks(int count);
  static int chunk_size(int count);
  // d_logits (count × cs: channel 0 = dℓ̄/dz, padding channels 0) and losses[slot] = mean ℓ
  // over count pixels of targets y ∈ [0, 1] (compact, count floats). Enqueued, no wait.
  void loss_grad(const cl::Buffer& logits, int count, int cs, const cl::Buffer& target,
                 cl::Buffer& d_logits, cl::Buffer& losses, int slot);
  // probs[i] = σ(logits[i·cs]), i < count (compact). Enqueued.
  void sigmoid(const cl::Buffer& logits, int count, int cs, cl::Buffer& probs);

 private:
  cl::Runtime& rt_;
  cl::Kernel partial_k_, sum_k_, sigmoid_k_;
  cl::Buffer partial_;
};

}  // namespace sgnlf::conv
