// Volume rendering of LiDAR rays on the device (method.md §0): raw densities h0 (N) and raw
// head outputs (N x 2: return-probability logit, intensity logit) along ray-major samples t
// become per-ray (depth, return probability, intensity) (n_rays x 3), with the sample
// weights; the backward turns dL/d(depth, prob, intensity) into dL/dh0 (N) and dL/dhead
// (N x 2). trunc_exp and the sigmoids are applied inside. The last sample's δ is the uniform
// bin width (far − near)/n_samples (torch-ngp / LiDAR-NeRF). The device profile's
// ray_work_items chooses the forward's, weights' and backward's kernels when the renderer is
// made: 1 = kernels/render/volume.cl (one work-item per ray), more = kernels/render/
// volume_slices.cl (a slice of that many work-items per ray; render/ray_slices.hpp). The median
// depth and the depth spread (evaluation only) run volume.cl's in both. Calls only enqueue.
#pragma once
#include "cl/runtime.hpp"
#include "render/ray_slices.hpp"
#include "render/render_config.hpp"

namespace sgnlf::render {

class VolumeRenderer {
 public:
  VolumeRenderer(cl::Runtime& rt, const RenderConfig& cfg, float scene_scale);

  float last_delta() const { return last_delta_; }

  // out: n_rays x 3; weights: N (needed by backward(); also for importance sampling).
  cl::Event forward(const cl::Buffer& t, const cl::Buffer& h0, const cl::Buffer& head, int n_rays,
                    int n_samples, cl::Buffer& out, cl::Buffer& weights);
  // Weights only, from densities alone (coarse pass of importance sampling).
  cl::Event weights(const cl::Buffer& t, const cl::Buffer& h0, int n_rays, int n_samples,
                    cl::Buffer& weights);
  // `weights` must be the forward's weights for the same inputs.
  cl::Event backward(const cl::Buffer& t, const cl::Buffer& h0, const cl::Buffer& head,
                     const cl::Buffer& weights, const cl::Buffer& grad_out, int n_rays,
                     int n_samples, cl::Buffer& grad_h0, cl::Buffer& grad_head);
  // Evaluation only (no backward): replaces each ray's depth in `out` by its median depth, the
  // range where the transmittance falls to 1/2 (exact for a density constant over each sample's
  // interval; the last sample's t if the weights never reach 1/2). `weights` must be
  // forward()'s for the same rays.
  cl::Event median_depth(const cl::Buffer& t, const cl::Buffer& weights, int n_rays,
                         int n_samples, cl::Buffer& out);
  // The spread of each ray's weights (kernels/render/volume.cl, render_depth_spread): stats
  // (n_rays × 2) = (opacity Σ w, weight-normalised depth variance), normalised units².
  cl::Event depth_spread(const cl::Buffer& t, const cl::Buffer& weights, int n_rays,
                         int n_samples, cl::Buffer& stats);

 private:
  void check(const char* what, const cl::Buffer& t, const cl::Buffer& h0, int n_rays,
             int n_samples) const;
  cl::Event launch(cl::Kernel& k, int n_rays, const char* what);
  float last_delta_;
  RaySlices slices_;
  cl::Kernel fwd_k_, weights_k_, bwd_k_, median_k_, spread_k_;
};

}  // namespace sgnlf::render
