// SurfaceSampler: launcher of render_sample_surface (kernels/render/surface.cl).
#include "render/surface_sampler.hpp"

#include "render/launch.hpp"

namespace sgnlf::render {

SurfaceSampler::SurfaceSampler(cl::Runtime& rt, const RenderConfig& cfg, float scene_scale)
    : cfg_(cfg),
      scale_(scene_scale),
      near_(cfg.near_m * scene_scale),
      far_(cfg.far_m * scene_scale),
      // Under the gpu profile (ray_work_items > 1) one work-item per sample: the same samples.
      wide_(rt.device_profile().ray_work_items > 1),
      k_(rt.kernel("render/surface.cl",
                   wide_ ? "render_sample_surface_wide" : "render_sample_surface")) {
  cfg_.validate("SurfaceSampler");
  require(scene_scale > 0.0f, "SurfaceSampler: scene_scale must be positive");
  require(cfg_.surface_sampling(), "SurfaceSampler: render.surface_band_samples is 0");
}

cl::Event SurfaceSampler::sample(const cl::Buffer& origins, const cl::Buffer& dirs,
                                 const cl::Buffer& target, int n_rays, bool jitter,
                                 uint64_t seed, uint32_t step, cl::Buffer& t, cl::Buffer& x) {
  const size_t n = size_t(n_rays) * size_t(samples());
  require(n_rays >= 0 && n < (size_t(1) << 31), "SurfaceSampler::sample: bad n_rays");
  check_floats(origins, size_t(n_rays) * 3, "SurfaceSampler::sample origins");
  check_floats(dirs, size_t(n_rays) * 3, "SurfaceSampler::sample dirs");
  check_floats(target, size_t(n_rays) * 3, "SurfaceSampler::sample target");
  check_floats(t, n, "SurfaceSampler::sample t");
  check_floats(x, n * 3, "SurfaceSampler::sample x");
  k_.set_args(n_rays, cfg_.surface_free_samples, cfg_.surface_band_samples,
              cfg_.surface_behind_samples, near_, far_, half_width(step),
              cfg_.surface_behind_m * scale_, int(jitter), uint32_t(seed), uint32_t(seed >> 32),
              step, origins, dirs, target, t, x);
  return launch_1d(k_, wide_ ? n : size_t(n_rays));
}

}  // namespace sgnlf::render
