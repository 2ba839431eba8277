// Training samples placed by the measured return (render.surface_* keys, render_config.hpp;
// kernels/render/surface.cl): a band around each training ray's return, stratified free space
// in front of it and a few samples behind it; rays without a return stratified over [near,
// far]. The peers sample uniformly (768 per ray); placing the samples where the LiDAR says the
// surface is gives a sharp field for a fraction of that. The return is a range along the ray
// in the frame's own LiDAR frame, so it holds for pose-free methods whatever the pose estimate.
// Every call only enqueues; results for the same (seed, step) are bit-identical.
#pragma once
#include <cstdint>

#include "cl/runtime.hpp"
#include "render/render_config.hpp"

namespace sgnlf::render {

class SurfaceSampler {
 public:
  SurfaceSampler(cl::Runtime& rt, const RenderConfig& cfg, float scene_scale);

  int samples() const { return cfg_.surface_samples(); }  // per ray
  float near() const { return near_; }
  float far() const { return far_; }
  // The band's half-width at `step`, normalised.
  float half_width(long step) const { return cfg_.surface_band_m(step) * scale_; }

  // samples() per ray (t: n_rays · samples(), x: n_rays · samples() × 3) from the targets
  // (n_rays × 3: normalised range, intensity, return label), the band's width at `step`.
  cl::Event sample(const cl::Buffer& origins, const cl::Buffer& dirs, const cl::Buffer& target,
                   int n_rays, bool jitter, uint64_t seed, uint32_t step, cl::Buffer& t,
                   cl::Buffer& x);

 private:
  RenderConfig cfg_;
  float scale_, near_, far_;
  bool wide_;  // the profile's ray_work_items > 1 when made: one work-item per sample
  cl::Kernel k_;
};

}  // namespace sgnlf::render
