// RangeLoss: launchers of kernels/render/loss.cl.
#include "render/range_loss.hpp"

#include <string>

#include "render/launch.hpp"

namespace sgnlf::render {

namespace {
// The reduction's work-group size: 256, or the largest power of two the device allows.
size_t reduce_group_size(const cl::Runtime& rt) {
  size_t wg = 256;
  while (wg > 1 && wg > rt.device().max_work_group_size) wg /= 2;
  return wg;
}
}  // namespace

RangeLoss::RangeLoss(cl::Runtime& rt, const RenderConfig& cfg, float scene_scale,
                     float label_smoothing)
    : cfg_(cfg),
      scene_scale_(scene_scale),
      smooth_(label_smoothing),
      reduce_wg_(reduce_group_size(rt)),
      range_k_(rt.kernel("render/loss.cl", "render_loss_range")),
      patch_k_(rt.kernel("render/loss.cl", "render_loss_patchgrad")),
      reduce_k_(rt.kernel("render/loss.cl", "render_loss_reduce",
                          "-DRENDER_REDUCE_WG=" + std::to_string(reduce_wg_))) {
  cfg_.validate("RangeLoss");
  require(scene_scale > 0.0f, "RangeLoss: scene_scale must be positive");
  require(label_smoothing >= 0.0f && label_smoothing < 0.5f,
          "RangeLoss: label_smoothing must be in [0, 0.5), got " + std::to_string(label_smoothing));
}

cl::Event RangeLoss::reduce(const cl::Buffer& in, int n, int stride, int offset, float scale,
                            cl::Buffer& loss, int index) {
  require(n >= 0 && stride > 0 && offset >= 0 && index >= 0, "RangeLoss::reduce: bad shape");
  if (n > 0) check_floats(in, size_t(offset) + size_t(n - 1) * size_t(stride) + 1, "RangeLoss::reduce in");
  check_floats(loss, size_t(index) + 1, "RangeLoss::reduce loss");
  reduce_k_.set_args(n, stride, offset, scale, in, loss, index);
  return reduce_k_.launch({reduce_wg_}, {reduce_wg_});
}

cl::Event RangeLoss::range(const cl::Buffer& out, const cl::Buffer& target, int n_rays,
                           cl::Buffer& grad_out, cl::Buffer& terms, cl::Buffer& loss) {
  require(n_rays > 0, "RangeLoss::range: n_rays must be positive, got " + std::to_string(n_rays));
  const size_t n3 = 3 * size_t(n_rays);
  check_floats(out, n3, "RangeLoss::range out");
  check_floats(target, n3, "RangeLoss::range target");
  check_floats(grad_out, n3, "RangeLoss::range grad_out");
  check_floats(terms, n3, "RangeLoss::range terms");
  check_floats(loss, kLossFloats, "RangeLoss::range loss");
  const float inv_n = 1.0f / float(n_rays);
  range_k_.set_args(n_rays, cfg_.weights.depth, cfg_.weights.ret, cfg_.weights.intensity, smooth_,
                    inv_n, out, target, terms, grad_out);
  launch_1d(range_k_, size_t(n_rays));
  reduce(terms, n_rays, 3, 0, inv_n, loss, 0);
  reduce(terms, n_rays, 3, 1, inv_n, loss, 1);
  return reduce(terms, n_rays, 3, 2, inv_n, loss, 2);
}

cl::Event RangeLoss::patch_gradient(const cl::Buffer& out, const cl::Buffer& target, int n_patches,
                                    cl::Buffer& grad_out, cl::Buffer& terms, cl::Buffer& loss) {
  const int rows = cfg_.patch_rows, cols = cfg_.patch_cols;
  require(n_patches > 0, "RangeLoss::patch_gradient: n_patches must be positive, got " +
                             std::to_string(n_patches));
  const size_t n = size_t(n_patches) * rows * cols;
  check_floats(out, 3 * n, "RangeLoss::patch_gradient out");
  check_floats(target, 3 * n, "RangeLoss::patch_gradient target");
  check_floats(grad_out, 3 * n, "RangeLoss::patch_gradient grad_out");
  check_floats(terms, n, "RangeLoss::patch_gradient terms");
  check_floats(loss, kLossFloats, "RangeLoss::patch_gradient loss");
  const double pairs = double(n_patches) * (rows * (cols - 1) + (rows - 1) * cols);
  const float inv_pairs = float(1.0 / pairs);
  patch_k_.set_args(int(n), rows, cols, int(cfg_.grad_l1), cfg_.weights.grad, 1.0f / scene_scale_,
                    cfg_.grad_clip_m, inv_pairs, out, target, terms, grad_out);
  launch_1d(patch_k_, n);
  return reduce(terms, int(n), 1, 0, inv_pairs, loss, 3);
}

RangeLossValues RangeLoss::read_losses(const cl::Buffer& loss) {
  check_floats(loss, kLossFloats, "RangeLoss::read_losses");
  const auto v = loss.read_vec<float>(kLossFloats);
  return {v[0], v[1], v[2], v[3]};
}

}  // namespace sgnlf::render
