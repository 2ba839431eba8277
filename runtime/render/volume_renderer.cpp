// VolumeRenderer: launchers of kernels/render/volume.cl and volume_slices.cl.
#include "render/volume_renderer.hpp"

#include <string>

#include "render/launch.hpp"

namespace sgnlf::render {

VolumeRenderer::VolumeRenderer(cl::Runtime& rt, const RenderConfig& cfg, float scene_scale)
    : last_delta_(cfg.bin_width(scene_scale)),
      slices_(rt.device_profile()),
      fwd_k_(slices_.sliced() ? rt.kernel("render/volume_slices.cl", "render_volume_fwd_slices",
                                           slices_.defines())
                              : rt.kernel("render/volume.cl", "render_volume_fwd")),
      weights_k_(slices_.sliced() ? rt.kernel("render/volume_slices.cl",
                                               "render_volume_weights_slices", slices_.defines())
                                  : rt.kernel("render/volume.cl", "render_volume_weights")),
      bwd_k_(slices_.sliced() ? rt.kernel("render/volume_slices.cl", "render_volume_bwd_slices",
                                           slices_.defines())
                              : rt.kernel("render/volume.cl", "render_volume_bwd")),
      median_k_(rt.kernel("render/volume.cl", "render_median_depth")),
      spread_k_(rt.kernel("render/volume.cl", "render_depth_spread")) {
  cfg.validate("VolumeRenderer");
  require(scene_scale > 0.0f, "VolumeRenderer: scene_scale must be positive");
}

cl::Event VolumeRenderer::launch(cl::Kernel& k, int n_rays, const char* what) {
  return slices_.sliced() ? slices_.launch(k, n_rays, what) : launch_1d(k, size_t(n_rays));
}

void VolumeRenderer::check(const char* what, const cl::Buffer& t, const cl::Buffer& h0, int n_rays,
                           int n_samples) const {
  const std::string w = std::string("VolumeRenderer::") + what;
  require(n_rays >= 0 && n_samples > 0 && size_t(n_rays) * n_samples < (size_t(1) << 31),
          w + ": bad shape n_rays = " + std::to_string(n_rays) +
              ", n_samples = " + std::to_string(n_samples));
  const size_t n = size_t(n_rays) * n_samples;
  check_floats(t, n, w + " t");
  check_floats(h0, n, w + " h0");
}

cl::Event VolumeRenderer::forward(const cl::Buffer& t, const cl::Buffer& h0, const cl::Buffer& head,
                                  int n_rays, int n_samples, cl::Buffer& out, cl::Buffer& weights) {
  check("forward", t, h0, n_rays, n_samples);
  const size_t n = size_t(n_rays) * n_samples;
  check_floats(head, 2 * n, "VolumeRenderer::forward head");
  check_floats(out, 3 * size_t(n_rays), "VolumeRenderer::forward out");
  check_floats(weights, n, "VolumeRenderer::forward weights");
  fwd_k_.set_args(n_rays, n_samples, last_delta_, t, h0, head, out, weights);
  return launch(fwd_k_, n_rays, "VolumeRenderer::forward");
}

cl::Event VolumeRenderer::weights(const cl::Buffer& t, const cl::Buffer& h0, int n_rays,
                                  int n_samples, cl::Buffer& weights) {
  check("weights", t, h0, n_rays, n_samples);
  check_floats(weights, size_t(n_rays) * n_samples, "VolumeRenderer::weights weights");
  weights_k_.set_args(n_rays, n_samples, last_delta_, t, h0, weights);
  return launch(weights_k_, n_rays, "VolumeRenderer::weights");
}

cl::Event VolumeRenderer::backward(const cl::Buffer& t, const cl::Buffer& h0,
                                   const cl::Buffer& head, const cl::Buffer& weights,
                                   const cl::Buffer& grad_out, int n_rays, int n_samples,
                                   cl::Buffer& grad_h0, cl::Buffer& grad_head) {
  check("backward", t, h0, n_rays, n_samples);
  const size_t n = size_t(n_rays) * n_samples;
  check_floats(head, 2 * n, "VolumeRenderer::backward head");
  check_floats(weights, n, "VolumeRenderer::backward weights");
  check_floats(grad_out, 3 * size_t(n_rays), "VolumeRenderer::backward grad_out");
  check_floats(grad_h0, n, "VolumeRenderer::backward grad_h0");
  check_floats(grad_head, 2 * n, "VolumeRenderer::backward grad_head");
  bwd_k_.set_args(n_rays, n_samples, last_delta_, t, h0, head, weights, grad_out, grad_h0,
                  grad_head);
  return launch(bwd_k_, n_rays, "VolumeRenderer::backward");
}

cl::Event VolumeRenderer::median_depth(const cl::Buffer& t, const cl::Buffer& weights, int n_rays,
                                       int n_samples, cl::Buffer& out) {
  require(n_rays >= 0 && n_samples > 0 && size_t(n_rays) * n_samples < (size_t(1) << 31),
          "VolumeRenderer::median_depth: bad shape n_rays = " + std::to_string(n_rays) +
              ", n_samples = " + std::to_string(n_samples));
  check_floats(t, size_t(n_rays) * n_samples, "VolumeRenderer::median_depth t");
  check_floats(weights, size_t(n_rays) * n_samples, "VolumeRenderer::median_depth weights");
  check_floats(out, 3 * size_t(n_rays), "VolumeRenderer::median_depth out");
  median_k_.set_args(n_rays, n_samples, last_delta_, t, weights, out);
  return launch_1d(median_k_, size_t(n_rays));
}

cl::Event VolumeRenderer::depth_spread(const cl::Buffer& t, const cl::Buffer& weights, int n_rays,
                                       int n_samples, cl::Buffer& stats) {
  require(n_rays >= 0 && n_samples > 0,
          "VolumeRenderer::depth_spread: bad shape n_rays = " + std::to_string(n_rays) +
              ", n_samples = " + std::to_string(n_samples));
  check_floats(t, size_t(n_rays) * n_samples, "VolumeRenderer::depth_spread t");
  check_floats(weights, size_t(n_rays) * n_samples, "VolumeRenderer::depth_spread weights");
  check_floats(stats, 2 * size_t(n_rays), "VolumeRenderer::depth_spread stats");
  spread_k_.set_args(n_rays, n_samples, t, weights, stats);
  return launch_1d(spread_k_, size_t(n_rays));
}

}  // namespace sgnlf::render
