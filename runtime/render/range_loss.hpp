// The LiDAR range loss on the device (method.md §0) and LiDAR-NeRF's range-image gradient
// loss on patch batches (§1), both as the batch mean with its gradient dL/d(depth, prob,
// intensity) (n_rays x 3). Per-ray terms go to a buffer; each scalar is then summed on the
// device by one work-group in a fixed order (strided slices, then a fixed tree), so the loss
// is bit-identical from run to run. Targets are n_rays x 3 (range in normalised units,
// intensity, return label 0/1). Calls only enqueue; read_losses() reads the four scalars.
#pragma once
#include "cl/runtime.hpp"
#include "render/render_config.hpp"

namespace sgnlf::render {

// The loss buffer's first four floats, in this order (read_losses; the training step reports
// them through its loss terms, pipeline/model/loss_terms.hpp).
struct RangeLossValues {
  float depth = 0, ret = 0, intensity = 0, grad = 0;
  float total() const { return depth + ret + intensity + grad; }
};
inline constexpr size_t kLossFloats = 4;

class RangeLoss {
 public:
  // label_smoothing s in [0, 0.5): the return term's target is clamp(label, s, 1 − s)
  // (LiDAR4D's ray-drop label smoothing); the depth and intensity masks stay the 0/1 label.
  RangeLoss(cl::Runtime& rt, const RenderConfig& cfg, float scene_scale,
            float label_smoothing = 0.0f);
  float label_smoothing() const { return smooth_; }

  // Writes grad_out (n_rays x 3) = d(mean loss)/d out, terms (n_rays x 3) and loss[0..2].
  cl::Event range(const cl::Buffer& out, const cl::Buffer& target, int n_rays, cl::Buffer& grad_out,
                  cl::Buffer& terms, cl::Buffer& loss);
  // Gradient loss over n_patches patch-major patches of patch_rows × patch_cols rays: ADDS
  // its gradient to grad_out[:, 0] (enqueue after range()), writes terms (n_rays), loss[3].
  // Pairs of horizontal and vertical neighbours count when both have a GT return and
  // |GT step| < grad_clip_m; differences are in metres (LiDAR-NeRF divides by the scale);
  // the mean runs over all pairs (masked ones count as zero). LiDAR-NeRF's code differs in
  // three details kept out here: it uses column pairs only, compares |Δpred| with the signed
  // Δgt, and masks by the left pixel's return only.
  cl::Event patch_gradient(const cl::Buffer& out, const cl::Buffer& target, int n_patches,
                           cl::Buffer& grad_out, cl::Buffer& terms, cl::Buffer& loss);

  static RangeLossValues read_losses(const cl::Buffer& loss);
  // loss[index] = scale · Σ_{i<n} in[offset + i·stride], one work-group in a fixed tree
  // (render_loss_reduce: the loss values above; weight carving's sum under the device
  // profile's loss_reduce: device).
  cl::Event reduce(const cl::Buffer& in, int n, int stride, int offset, float scale,
                   cl::Buffer& loss, int index);

 private:
  RenderConfig cfg_;
  float scene_scale_;
  float smooth_ = 0.0f;
  size_t reduce_wg_;
  cl::Kernel range_k_, patch_k_, reduce_k_;
};

}  // namespace sgnlf::render
