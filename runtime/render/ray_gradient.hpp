// Per-ray gradient of the sample positions x_i = o + t_i d (kernels/render/ray_grad.cl):
// dL/do = Σ_i dL/dx_i and dL/dd = Σ_i t_i dL/dx_i, in a fixed order. The pipeline adds the
// direction encoding's gradient to dL/dd and hands both to pose_gradient() (pose-free methods).
// reduce_rows runs kernels/render/ray_grad_slices.cl under a device profile whose ray_work_items
// is above 1 (a slice of work-items per ray; render/ray_slices.hpp), ray_grad.cl's otherwise.
#pragma once
#include "cl/runtime.hpp"
#include "render/ray_slices.hpp"

namespace sgnlf::render {

class RayGradReducer {
 public:
  explicit RayGradReducer(cl::Runtime& rt);
  // t: n_rays·S, grad_x: n_rays·S x 3 -> grad_o, grad_d: n_rays x 3. Only enqueues.
  cl::Event reduce(const cl::Buffer& t, const cl::Buffer& grad_x, int n_rays, int n_samples,
                   cl::Buffer& grad_o, cl::Buffer& grad_d);
  // The reduction over each ray's first count[r] samples stored as rows offset[r] + i of
  // grad_x (offset: n_rays + 1 int32, or nullptr for the full layout, count = M); t, o, d in the
  // full R × M layout. Components of x = o + t·d outside [−bound, bound] (clamped before the
  // field) contribute nothing. Only enqueues.
  cl::Event reduce_rows(const cl::Buffer* offset, const cl::Buffer& t, const cl::Buffer& o,
                        const cl::Buffer& d, const cl::Buffer& grad_x, int n_rays, int M,
                        float bound, cl::Buffer& grad_o, cl::Buffer& grad_d);

 private:
  RaySlices slices_;
  cl::Kernel k_, rows_;
};

}  // namespace sgnlf::render
