// One loss of the training objective (issue 67 item 3): its name, its gradient and its value.
// The model keeps one list of terms (loss_terms.hpp builds the config's, a step part adds its
// own with LidarNerfModel::add_loss) and runs a training step through it, in this order:
//   1. add_field_gradient(FieldPass&): a term with a pass of its own through the field (SG-NLF's
//      cross-frame consistency renders rays of another frame, LiDAR4D's flow supervision
//      evaluates the flow field); the pass hands out the rendered rays' context, which its
//      backward takes, and writes the step's second gradient;
//   2. the batch's sample and forward; the range loss writes the per-ray output gradient
//      (RangeTerm::write_output_gradient), then every add_output_gradient(LossPass&) adds;
//   3. inside the renderer's backward, add_sample_gradient(LossPass&) (per sample);
//   4. the backward, the two gradients summed;
//   5. take_own_step(OwnGroupStep&): a term that trains a parameter group outside the field's
//      flat buffer on an objective of its own, with that group's own optimiser (SG-NLF's
//      spectral embedding Ψ, method.md §4.1), takes its step, after the batch's backward has
//      used the group's activations;
//   then the step's optimiser (train/field_optimizer.hpp) takes one Adam step of the field.
// Each hook receives what it may use, so a term cannot run before what it needs exists: the
// batch's terms get the forward's outputs (LossPass), a term with its own pass gets a FieldPass,
// a term with its own parameter group an OwnGroupStep.
// report() writes the term's value(s) of the last step into the LossReport the trainer logs and
// checks for divergence.
#pragma once
#include <functional>
#include <memory>
#include <vector>

#include "cl/runtime.hpp"
#include "pipeline/model/forward_context.hpp"
#include "pipeline/model/loss_report.hpp"
#include "pipeline/model/ray_batch.hpp"

namespace sgnlf::spectral {
struct SurfacePoint;
}

namespace sgnlf::pipeline {

class LidarNerfModel;

// The batch's forward as the terms see it: the batch, the renderer's forward (t, h0, weights:
// n_rays × per_ray; out: n_rays × 3), the targets (n_rays × 3) and the gradients they add to.
struct LossPass {
  const RayBatch& batch;
  long step;
  int n_rays, per_ray;
  const cl::Buffer &out, &target, &t, &h0, &weights;
  cl::Buffer &grad_out, &terms, &loss_buf;  // grad_out: n_rays × 3; loss_buf: kLossBufferFloats
  cl::Buffer& g_h0;                          // n_rays × per_ray, the renderer's dL/dh0
  // The batch's world directions on the device (n_rays × 3).
  const cl::Buffer& directions;
};

// Per ray (n × 3 each, normalised frame): dL/d(origin) and dL/d(direction), the direction
// encoding's share included.
struct RayGrads {
  std::vector<float> origin, direction;
};

// Rays a FieldPass rendered: n × 3 (depth normalised, return probability, intensity) and the
// context their backward takes (valid until the next pass of the model).
struct RenderedRays {
  std::vector<float> out;
  ForwardContext context;
  int n = 0;
};

// A term's own pass through the field within a training step, before the batch's (step 1
// above). Its gradient goes into the step's second gradient buffer, which the model adds to the
// batch's before the Adam step: λ·L of one objective, one Adam step (method.md §4.4: a separate
// step would move the parameters by ≈ lr whatever λ is, and count Adam's steps twice). One term
// writes it per step.
class FieldPass {
 public:
  FieldPass(LidarNerfModel& model, const RayBatch& batch, uint64_t seed, long step)
      : batch(batch), seed(seed), step(step), model_(model) {}
  const RayBatch& batch;  // the step's batch (its frame, its rays)
  const uint64_t seed;
  const long step;

  // Training-mode forward of n rays (origins, directions: n × 3) with the protocol's sampling,
  // jitter per the config from (seed, step). Blocking (reads the outputs).
  RenderedRays render(const std::vector<float>& origins, const std::vector<float>& directions,
                      int n);
  // dL/d(depth, return probability, intensity) of those rays (n × 3, the term's weight
  // applied) through their context's backward into the step's second gradient; with
  // `ray_grads`, the rays' gradients (blocking). Throws when another pass ran since render().
  RayGrads backward(const RenderedRays& rays, const std::vector<float>& grad_out, bool ray_grads);
  // LiDAR4D's flow field at n points x (n × 3, normalised box) at the frame's time: `loss` maps
  // the flow (n × 6: forward, backward) to its value and writes dL/dflow (n × 6); the flow
  // field's parameter gradient goes into the step's second gradient. Returns the value.
  // Blocking (one read of the flow). Needs the 4D encoder.
  using FlowLoss = std::function<double(const std::vector<float>& flow, std::vector<float>& d_flow)>;
  double flow(const std::vector<float>& x, int n, const FlowLoss& loss);
  // The same with the points and the loss on the device (x: n × 3, unchanged until the step
  // ends): `loss` enqueues dL/dflow (n × 6) from the flow (n × 6). Nothing is read back.
  using DeviceFlowLoss = std::function<void(const cl::Buffer& flow, cl::Buffer& d_flow)>;
  void flow(const cl::Buffer& x, int n, const DeviceFlowLoss& loss);
  cl::Runtime& runtime() const;
  // Whether a term wrote the second gradient (the model then adds it).
  bool wrote_gradient() const { return wrote_; }

 private:
  void claim(const char* who);
  LidarNerfModel& model_;
  bool wrote_ = false;
};

// A term's step on a parameter group of the field that is not in the flat buffer (step 5
// above), with the term's own optimiser: SG-NLF's Ψ, which trains only on the spectral loss
// (the range loss reaches the positions through Ψ, never its weights). Needs the hybrid
// encoder (sgnlf::Error naming the call without it).
class OwnGroupStep {
 public:
  OwnGroupStep(LidarNerfModel& model, uint64_t seed, long step)
      : seed(seed), step(step), model_(model) {}
  const uint64_t seed;
  const long step;
  // The spectral loss of a batch of surface samples (normalised box, weights summing to 1) and
  // its gradient with respect to Ψ into psi().grad. Returns the loss (blocking).
  double spectral_gradient(const std::vector<spectral::SurfacePoint>& batch);
  // Ψ's parameters and that gradient, `count` floats each, for the term's optimiser.
  struct Group {
    cl::Buffer& params;
    const cl::Buffer& grad;
    size_t count;
  };
  Group psi();

 private:
  LidarNerfModel& model_;
};

class LossTerm {
 public:
  virtual ~LossTerm() = default;
  virtual const char* name() const = 0;
  // Step 1: a pass of its own through the field.
  virtual void add_field_gradient(FieldPass&) {}
  // Step 2: per ray, added to pass.grad_out (and its value into pass.loss_buf).
  virtual void add_output_gradient(LossPass&) {}
  // Step 3: per sample, after the renderer's backward: added to pass.g_h0.
  virtual void add_sample_gradient(LossPass&) {}
  // Step 5: a step of a parameter group of its own, on its own objective.
  virtual void take_own_step(OwnGroupStep&) {}
  // Its value(s) of the last step into `r`. `loss` is the model's loss buffer (the range and
  // patch terms' values, carving's device sum), read once for every term; a term whose value
  // lives elsewhere reads it here (blocking).
  virtual void report(LossReport& r, const std::vector<float>& loss) const = 0;
};

}  // namespace sgnlf::pipeline
