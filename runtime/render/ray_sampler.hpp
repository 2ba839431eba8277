// Sample positions along LiDAR rays (method.md §0) on the device: stratified uniform samples
// with Philox jitter (or midpoints for evaluation) and importance samples from a coarse pass's
// weights, merged sorted. Inputs are origins and unit directions (n_rays x 3, normalised
// frame); outputs t (n_rays·S, ray-major) and x = o + t·d (n_rays·S x 3). Every call only
// enqueues; results for the same (seed, step) are bit-identical.
#pragma once
#include <cstdint>

#include "cl/runtime.hpp"
#include "render/render_config.hpp"

namespace sgnlf::render {

class RaySampler {
 public:
  RaySampler(cl::Runtime& rt, const RenderConfig& cfg, float scene_scale);

  int uniform_samples() const { return cfg_.n_samples; }
  int merged_samples() const { return cfg_.n_samples + cfg_.n_importance; }
  float near() const { return near_; }
  float far() const { return far_; }

  // cfg.n_samples samples per ray; `jitter` false gives bin midpoints.
  cl::Event uniform(const cl::Buffer& origins, const cl::Buffer& dirs, int n_rays, bool jitter,
                    uint64_t seed, uint32_t step, cl::Buffer& t, cl::Buffer& x);
  // cfg.n_importance samples per ray drawn from w_coarse (n_rays x n_coarse, e.g. from
  // VolumeRenderer::weights) and merged with t_coarse: n_coarse + n_importance per ray.
  // src_out (int per merged sample): k for coarse sample k, n_coarse + j for fine sample j.
  // t_coarse sorted per ray. Under the gpu profile (ray_work_items > 1) one work-item per
  // output sample (render_sample_importance_wide): the same samples within the CDF's rounding.
  cl::Event importance(const cl::Buffer& origins, const cl::Buffer& dirs, int n_rays, int n_coarse,
                       const cl::Buffer& t_coarse, const cl::Buffer& w_coarse, bool jitter,
                       uint64_t seed, uint32_t step, cl::Buffer& t_out, cl::Buffer& x_out,
                       cl::Buffer& src_out);

 private:
  RenderConfig cfg_;
  float near_, far_;
  cl::Kernel uniform_k_, importance_k_;
  // The profile's ray_work_items and local_size when made (1: the per-ray kernel).
  int ray_wi_, ray_wg_;
  size_t local_mem_bytes_;
};

}  // namespace sgnlf::render
