// RayGradReducer: launcher of kernels/render/ray_grad.cl and ray_grad_slices.cl.
#include "render/ray_gradient.hpp"

#include "render/launch.hpp"

namespace sgnlf::render {

RayGradReducer::RayGradReducer(cl::Runtime& rt)
    : slices_(rt.device_profile()),
      k_(rt.kernel("render/ray_grad.cl", "render_raygrad_reduce")),
      rows_(slices_.sliced() ? rt.kernel("render/ray_grad_slices.cl",
                                         "render_raygrad_reduce_rows_slices", slices_.defines())
                             : rt.kernel("render/ray_grad.cl", "render_raygrad_reduce_rows")) {}

cl::Event RayGradReducer::reduce(const cl::Buffer& t, const cl::Buffer& grad_x, int n_rays,
                                 int n_samples, cl::Buffer& grad_o, cl::Buffer& grad_d) {
  require(n_rays >= 0 && n_samples > 0 && size_t(n_rays) * n_samples < (size_t(1) << 31),
          "RayGradReducer::reduce: bad shape");
  const size_t n = size_t(n_rays) * n_samples;
  check_floats(t, n, "RayGradReducer::reduce t");
  check_floats(grad_x, 3 * n, "RayGradReducer::reduce grad_x");
  check_floats(grad_o, 3 * size_t(n_rays), "RayGradReducer::reduce grad_o");
  check_floats(grad_d, 3 * size_t(n_rays), "RayGradReducer::reduce grad_d");
  k_.set_args(n_rays, n_samples, t, grad_x, grad_o, grad_d);
  return launch_1d(k_, size_t(n_rays));
}

cl::Event RayGradReducer::reduce_rows(const cl::Buffer* offset, const cl::Buffer& t,
                                      const cl::Buffer& o, const cl::Buffer& d,
                                      const cl::Buffer& grad_x, int n_rays, int M, float bound,
                                      cl::Buffer& grad_o, cl::Buffer& grad_d) {
  require(n_rays >= 0 && M > 0 && size_t(n_rays) * M < (size_t(1) << 31),
          "RayGradReducer::reduce_rows: bad shape");
  const size_t n = size_t(n_rays) * M;
  check_floats(t, n, "RayGradReducer::reduce_rows t");
  check_floats(o, 3 * size_t(n_rays), "RayGradReducer::reduce_rows o");
  check_floats(d, 3 * size_t(n_rays), "RayGradReducer::reduce_rows d");
  check_floats(grad_o, 3 * size_t(n_rays), "RayGradReducer::reduce_rows grad_o");
  check_floats(grad_d, 3 * size_t(n_rays), "RayGradReducer::reduce_rows grad_d");
  if (offset) check_floats(*offset, size_t(n_rays) + 1, "RayGradReducer::reduce_rows offset");
  else check_floats(grad_x, 3 * n, "RayGradReducer::reduce_rows grad_x");
  // Without an offset table the kernel never reads it; any valid buffer fills the slot.
  rows_.set_args(n_rays, M, bound, offset ? 1 : 0, offset ? *offset : t, t, o, d, grad_x, grad_o,
                 grad_d);
  if (slices_.sliced()) return slices_.launch(rows_, n_rays, "RayGradReducer::reduce_rows");
  return launch_1d(rows_, size_t(n_rays));
}

}  // namespace sgnlf::render
