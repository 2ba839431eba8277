// RaySampler: launchers of kernels/render/sample.cl.
#include "render/ray_sampler.hpp"

#include <algorithm>
#include <string>

#include "render/launch.hpp"

namespace sgnlf::render {

RaySampler::RaySampler(cl::Runtime& rt, const RenderConfig& cfg, float scene_scale)
    : cfg_(cfg),
      near_(cfg.near_m * scene_scale),
      far_(cfg.far_m * scene_scale),
      uniform_k_(rt.kernel("render/sample.cl", "render_sample_uniform")),
      ray_wi_(rt.device_profile().ray_work_items),
      ray_wg_(rt.device_profile().local_size),
      local_mem_bytes_(size_t(rt.device().local_mem_bytes)) {
  importance_k_ =
      ray_wi_ > 1
          ? rt.kernel("render/sample.cl", "render_sample_importance_wide",
                      "-DRAY_WI=" + std::to_string(ray_wi_) + " -DRAY_WG=" + std::to_string(ray_wg_))
          : rt.kernel("render/sample.cl", "render_sample_importance");
  cfg_.validate("RaySampler");
  require(scene_scale > 0.0f, "RaySampler: scene_scale must be positive");
}

cl::Event RaySampler::uniform(const cl::Buffer& origins, const cl::Buffer& dirs, int n_rays,
                              bool jitter, uint64_t seed, uint32_t step, cl::Buffer& t,
                              cl::Buffer& x) {
  const size_t n = size_t(n_rays) * cfg_.n_samples;
  require(n_rays >= 0 && n < (size_t(1) << 31), "RaySampler::uniform: bad n_rays");
  check_floats(origins, size_t(n_rays) * 3, "RaySampler::uniform origins");
  check_floats(dirs, size_t(n_rays) * 3, "RaySampler::uniform dirs");
  check_floats(t, n, "RaySampler::uniform t");
  check_floats(x, n * 3, "RaySampler::uniform x");
  uniform_k_.set_args(n_rays, cfg_.n_samples, near_, far_, int(jitter), uint32_t(seed),
                      uint32_t(seed >> 32), step, origins, dirs, t, x);
  return launch_1d(uniform_k_, size_t(n_rays) * ((cfg_.n_samples + 3) / 4));  // one per quad
}

cl::Event RaySampler::importance(const cl::Buffer& origins, const cl::Buffer& dirs, int n_rays,
                                 int n_coarse, const cl::Buffer& t_coarse,
                                 const cl::Buffer& w_coarse, bool jitter, uint64_t seed,
                                 uint32_t step, cl::Buffer& t_out, cl::Buffer& x_out,
                                 cl::Buffer& src_out) {
  const int n_fine = cfg_.n_importance;
  require(n_fine > 0, "RaySampler::importance: config has n_importance = 0");
  require(n_coarse > 0, "RaySampler::importance: n_coarse must be positive");
  const size_t nc = size_t(n_rays) * n_coarse, no = size_t(n_rays) * (n_coarse + n_fine);
  require(n_rays >= 0 && no < (size_t(1) << 31), "RaySampler::importance: bad n_rays");
  check_floats(origins, size_t(n_rays) * 3, "RaySampler::importance origins");
  check_floats(dirs, size_t(n_rays) * 3, "RaySampler::importance dirs");
  check_floats(t_coarse, nc, "RaySampler::importance t_coarse");
  check_floats(w_coarse, nc, "RaySampler::importance w_coarse");
  check_floats(t_out, no, "RaySampler::importance t_out");
  check_floats(x_out, no * 3, "RaySampler::importance x_out");
  check_floats(src_out, no, "RaySampler::importance src_out");  // int32: same size as float
  importance_k_.set_args(n_rays, n_coarse, n_fine, near_, far_, int(jitter), uint32_t(seed),
                         uint32_t(seed >> 32), step, origins, dirs, t_coarse, w_coarse, t_out,
                         x_out, src_out);
  if (ray_wi_ == 1) return launch_1d(importance_k_, size_t(n_rays));
  // Per ray in local memory: the CDF (n_coarse + 1 words) and the fine samples.
  const size_t rays_per_group = size_t(ray_wg_ / ray_wi_);
  const size_t local = rays_per_group * size_t(n_coarse + 1 + n_fine) * sizeof(float);
  if (local_mem_bytes_ != 0 && local + size_t(ray_wg_) * 4 > local_mem_bytes_)
    throw Error("RaySampler::importance: " + std::to_string(n_coarse) + " coarse and " +
                std::to_string(n_fine) + " fine samples per ray need " + std::to_string(local) +
                " bytes of local memory per work-group, more than the device's " +
                std::to_string(local_mem_bytes_));
  importance_k_.set_arg(16, cl::LocalMem{local});
  const size_t groups = (size_t(n_rays) + rays_per_group - 1) / rays_per_group;
  return importance_k_.launch({std::max<size_t>(groups, 1) * size_t(ray_wg_)}, {size_t(ray_wg_)});
}

}  // namespace sgnlf::render
