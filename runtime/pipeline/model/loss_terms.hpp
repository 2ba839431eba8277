// The training losses of LidarNerfModel (model.hpp) as a list of terms. Each term adds its
// gradient to one of two places of the backward: the per-ray output gradient dL/d(depth,
// return probability, intensity) before the renderer's backward (the range loss, the patch
// gradient loss, LiDAR4D's Chamfer term), or the per-sample σ-logit gradient after it (weight
// carving); and each reports its named value(s) into render::LossValues. The list is made from
// the config once (make_loss_terms) and run in its order; the range term comes first and WRITES
// the output gradient, every later term adds to it.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "cl/runtime.hpp"
#include "pipeline/config/train_config.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "render/range_loss.hpp"
#include "render/weight_carving.hpp"

namespace sgnlf::pipeline {

// The model's loss buffer: render::RangeLoss's kLossFloats (depth, ret, intensity, grad), then
// weight carving's sum when the device profile's loss_reduce is device (slot kCarveSlot).
inline constexpr size_t kCarveSlot = render::kLossFloats;
inline constexpr size_t kLossBufferFloats = render::kLossFloats + 1;

// One training pass as the terms see it: the batch, the renderer's forward (t, h0, weights:
// n_rays × per_ray; out: n_rays × 3), the targets (n_rays × 3) and the gradients they add to.
struct LossPass {
  const RayBatch& batch;
  long step;
  int n_rays, per_ray;
  const cl::Buffer &out, &target, &t, &h0, &weights;
  cl::Buffer &grad_out, &terms, &loss_buf;  // grad_out: n_rays × 3; loss_buf: kLossBufferFloats
  cl::Buffer& g_h0;                          // n_rays × per_ray, the renderer's dL/dh0
  // The batch's world directions on the device (n_rays × 3; the Chamfer term under the device
  // profile's chamfer: device reads them there).
  const cl::Buffer* directions = nullptr;
};

class LossTerm {
 public:
  virtual ~LossTerm() = default;
  virtual const char* name() const = 0;
  // Before the renderer's backward: into pass.grad_out (and pass.loss_buf).
  virtual void add_output_gradient(LossPass&) {}
  // After the renderer's backward: into pass.g_h0.
  virtual void add_sample_gradient(LossPass&) {}
  // The term's value(s) of the last pass into v (its own fields of it; none for "chamfer",
  // which LossValues does not hold). Blocking.
  virtual void read(render::LossValues& v) const = 0;
  // The same from `loss`, a host copy of the loss buffer read once for every term (the device
  // profile's loss_reduce: device); a term whose value lives on the host reads it as read().
  virtual void read_copy(render::LossValues& v, const std::vector<float>& loss) const {
    (void)loss;
    read(v);
  }
  // The term's value of the last pass (the sum of its fields); 0 before the first. Blocking.
  virtual double value() const = 0;
};

// The config's terms, in order: "range" (depth, ret, intensity), "patch_gradient" (grad; on
// patch batches), "chamfer" (lidar4d.chamfer_weight > 0), "carve" (render.weights.carve > 0).
// `loss_buf` is the buffer the passes' loss_buf will be (the range and patch terms' values);
// `carve` is null when the config has no carving. Both, and `range`, must outlive the terms.
// `device_sums`: the device profile's loss_reduce is device (carving's terms summed into
// loss_buf[kCarveSlot] on the device). `device_chamfer`: the device profile's chamfer is device
// (the Chamfer term's neighbours, gradient and value on that runtime's device, its value read
// only when asked; null: on the host, 3 blocking transfers a pass).
std::vector<std::unique_ptr<LossTerm>> make_loss_terms(const TrainConfig& c, float scene_scale,
                                                        render::RangeLoss& range,
                                                        const cl::Buffer& loss_buf,
                                                        render::WeightCarving* carve,
                                                        bool device_sums = false,
                                                        cl::Runtime* device_chamfer = nullptr);

}  // namespace sgnlf::pipeline
