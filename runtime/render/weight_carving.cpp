// WeightCarving: launcher of render_weight_carve (kernels/render/surface.cl) and of
// render_weight_carve_slices (kernels/render/weight_carve_slices.cl).
#include "render/weight_carving.hpp"

#include <algorithm>

#include "render/launch.hpp"

namespace sgnlf::render {

WeightCarving::WeightCarving(cl::Runtime& rt, const RenderConfig& cfg, float scene_scale,
                             int max_rays)
    : cfg_(cfg),
      near_(cfg.near_m * scene_scale),
      last_delta_(cfg.bin_width(scene_scale)),
      max_rays_(max_rays),
      slices_(rt.device_profile()),
      terms_(rt, size_t(std::max(1, max_rays)) * sizeof(float)),
      k_(slices_.sliced() ? rt.kernel("render/weight_carve_slices.cl",
                                      "render_weight_carve_slices", slices_.defines())
                          : rt.kernel("render/surface.cl", "render_weight_carve")) {
  cfg_.validate("WeightCarving");
  require(scene_scale > 0.0f, "WeightCarving: scene_scale must be positive");
  require(max_rays > 0, "WeightCarving: max_rays must be positive");
}

cl::Event WeightCarving::add(const cl::Buffer& t, const cl::Buffer& h0, const cl::Buffer& weights,
                             const cl::Buffer& target, int n_rays, int M, float half_w,
                             cl::Buffer& g_h0) {
  require(n_rays > 0 && n_rays <= max_rays_ && M > 0,
          "WeightCarving::add: " + std::to_string(n_rays) + " rays (capacity " +
              std::to_string(max_rays_) + "), " + std::to_string(M) + " samples");
  const size_t n = size_t(n_rays) * size_t(M);
  check_floats(t, n, "WeightCarving::add t");
  check_floats(h0, n, "WeightCarving::add h0");
  check_floats(weights, n, "WeightCarving::add weights");
  check_floats(target, size_t(n_rays) * 3, "WeightCarving::add target");
  check_floats(g_h0, n, "WeightCarving::add g_h0");
  n_rays_ = n_rays;
  const float scale = cfg_.weights.carve / float(n_rays);
  k_.set_args(n_rays, M, last_delta_, near_, half_w, scale, t, h0, weights, target, g_h0, terms_);
  if (slices_.sliced()) return slices_.launch(k_, n_rays, "WeightCarving::add");
  return launch_1d(k_, size_t(n_rays));
}

double WeightCarving::read() const {
  if (n_rays_ == 0) return 0.0;
  const auto v = terms_.read_vec<float>(size_t(n_rays_));
  double s = 0.0;
  for (float x : v) s += double(x);
  return s;
}

}  // namespace sgnlf::render
