// Weight carving (NeuRAD's L_w; render.weights.carve, render_config.hpp; kernels/render/
// surface.cl): the mean over a batch's rays of carve · Σ_i w_i² over the samples farther than
// the surface band's half-width from the ray's return. It drives the weight of free space and
// of the space behind the return to zero, so the field becomes opaque at the surface instead of
// meeting the expected depth Σ w·t with weight spread around it. Rays without a return carry
// none. Every call only enqueues; read() blocks. Under a device profile whose ray_work_items is
// above 1 the kernel is kernels/render/weight_carve_slices.cl (a slice of work-items per ray;
// render/ray_slices.hpp), surface.cl's render_weight_carve otherwise.
#pragma once
#include "cl/runtime.hpp"
#include "render/ray_slices.hpp"
#include "render/render_config.hpp"

namespace sgnlf::render {

class WeightCarving {
 public:
  WeightCarving(cl::Runtime& rt, const RenderConfig& cfg, float scene_scale, int max_rays);

  // From the renderer's forward (t, h0, weights: n_rays × M) and the targets (n_rays × 3):
  // writes the per-ray terms and ADDS dL/dh0 to g_h0 (enqueue after VolumeRenderer::backward).
  // `half_w`: the band's half-width, normalised (SurfaceSampler::half_width).
  cl::Event add(const cl::Buffer& t, const cl::Buffer& h0, const cl::Buffer& weights,
                const cl::Buffer& target, int n_rays, int M, float half_w, cl::Buffer& g_h0);
  // The loss of the last add() (the sum of its per-ray terms, in ray order). Blocking.
  double read() const;
  // The per-ray terms of the last add() (n_rays() floats, summed by read()).
  const cl::Buffer& terms() const { return terms_; }
  int n_rays() const { return n_rays_; }

 private:
  RenderConfig cfg_;
  float near_, last_delta_;
  int max_rays_, n_rays_ = 0;
  RaySlices slices_;
  cl::Buffer terms_;
  cl::Kernel k_;
};

}  // namespace sgnlf::render
