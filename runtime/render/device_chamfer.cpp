// DeviceChamfer: launcher of kernels/render/chamfer.cl's Chamfer term.
#include "render/device_chamfer.hpp"

#include <algorithm>

#include "render/launch.hpp"

namespace sgnlf::render {

namespace {
constexpr size_t kWg = 64;      // CHAMFER_WG: points per local-memory tile and work-group
constexpr size_t kSumWg = 256;  // CHAMFER_SUM_WG

cl::Buffer floats(cl::Runtime& rt, size_t n) {
  return cl::Buffer(rt, std::max<size_t>(1, n) * sizeof(float));
}
}  // namespace

std::string chamfer_program_options() {
  return "-DCHAMFER_WG=" + std::to_string(kWg) + " -DCHAMFER_SUM_WG=" + std::to_string(kSumWg);
}

DeviceChamfer::DeviceChamfer(cl::Runtime& rt) : rt_(rt) {
  const std::string o = chamfer_program_options();
  nearest_ = rt.kernel("render/chamfer.cl", "render_chamfer_nearest", o);
  grad_ = rt.kernel("render/chamfer.cl", "render_chamfer_grad", o);
  sum_ = rt.kernel("render/chamfer.cl", "render_chamfer_sum", o);
  ray_points_ = rt.kernel("render/chamfer.cl", "render_chamfer_ray_points", o);
  ray_grad_ = rt.kernel("render/chamfer.cl", "render_chamfer_ray_grad", o);
}

void DeviceChamfer::ensure(int n_pred, int n_target) {
  if (size_t(n_pred) > cap1_) {
    cap1_ = size_t(n_pred);
    nn1_ = floats(rt_, cap1_), d1_ = floats(rt_, cap1_);  // int and float alike: 4 bytes
  }
  if (size_t(n_target) > cap2_) {
    cap2_ = size_t(n_target);
    nn2_ = floats(rt_, cap2_), d2_ = floats(rt_, cap2_);
  }
}

void DeviceChamfer::sum(int n1, const cl::Buffer& a, float c1, int n2, const cl::Buffer& b,
                        float c2, cl::Buffer& loss, int slot) {
  require(n1 >= 0 && n2 >= 0 && slot >= 0, "DeviceChamfer::sum: negative count or slot");
  check_floats(a, size_t(n1), "DeviceChamfer::sum a");
  check_floats(b, size_t(n2), "DeviceChamfer::sum b");
  check_floats(loss, size_t(slot) + 1, "DeviceChamfer::sum loss");
  sum_.set_args(n1, a, c1, n2, b, c2, loss, slot);
  sum_.launch({kSumWg}, {kSumWg});
}

void DeviceChamfer::run(const cl::Buffer& pred, int n_pred, const cl::Buffer& target,
                        int n_target, ChamferReduce reduce, float loss_scale,
                        const ChamferGradOut& g, cl::Buffer& loss, int slot) {
  require(n_pred >= 0 && n_target >= 0,
          "DeviceChamfer::run: " + std::to_string(n_pred) + " predicted and " +
              std::to_string(n_target) + " target points");
  require(g.out != nullptr && g.stride >= 3 && g.offset >= 0 && g.offset + 3 <= g.stride,
          "DeviceChamfer::run: gradient stride " + std::to_string(g.stride) + ", offset " +
              std::to_string(g.offset));
  check_floats(pred, size_t(n_pred) * 3, "DeviceChamfer::run pred");
  check_floats(target, size_t(n_target) * 3, "DeviceChamfer::run target");
  check_floats(*g.out, size_t(n_pred) * size_t(g.stride), "DeviceChamfer::run gradient");
  ensure(n_pred, n_target);
  const bool empty = n_pred == 0 || n_target == 0;
  // The host's scales (render::chamfer_loss): s = 0.5 / n (mean) or 0.5, gradient 2s.
  const bool mean = reduce == ChamferReduce::Mean;
  const double s1 = empty ? 0.0 : 0.5 / (mean ? double(n_pred) : 1.0);
  const double s2 = empty ? 0.0 : 0.5 / (mean ? double(n_target) : 1.0);
  if (!empty) {
    nearest_.set_args(n_pred, pred, n_target, target, nn1_, d1_);
    launch_1d(nearest_, size_t(n_pred));
    nearest_.set_args(n_target, target, n_pred, pred, nn2_, d2_);
    launch_1d(nearest_, size_t(n_target));
  }
  if (n_pred > 0) {
    grad_.set_args(n_pred, pred, empty ? 0 : n_target, target, nn1_, nn2_, float(2.0 * s1),
                   float(2.0 * s2), g.mul, *g.out, g.stride, g.offset, int(g.accumulate));
    launch_1d(grad_, size_t(n_pred));
  }
  sum(empty ? 0 : n_pred, d1_, float(loss_scale * s1), empty ? 0 : n_target, d2_,
      float(loss_scale * s2), loss, slot);
}

void DeviceChamfer::ray(const cl::Buffer& dir, const cl::Buffer& out, const cl::Buffer& target,
                        int n, float scale, float weight, cl::Buffer& grad_out, cl::Buffer& loss,
                        int slot) {
  require(n > 0 && scale > 0.0f, "DeviceChamfer::ray: " + std::to_string(n) + " rays, scale " +
                                     std::to_string(scale));
  const size_t n3 = size_t(n) * 3;
  check_floats(dir, n3, "DeviceChamfer::ray dir");
  check_floats(out, n3, "DeviceChamfer::ray out");
  check_floats(target, n3, "DeviceChamfer::ray target");
  check_floats(grad_out, n3, "DeviceChamfer::ray grad_out");
  if (size_t(n) > ray_cap_) {
    ray_cap_ = size_t(n);
    ray_pred_ = floats(rt_, n3), ray_target_ = floats(rt_, n3), ray_g_ = floats(rt_, n3);
  }
  ray_points_.set_args(n, dir, out, target, scale, ray_pred_, ray_target_);
  launch_1d(ray_points_, size_t(n));
  ChamferGradOut g;
  g.out = &ray_g_;
  run(ray_pred_, n, ray_target_, n, ChamferReduce::Mean, weight, g, loss, slot);
  ray_grad_.set_args(n, dir, ray_g_, target, weight, scale, grad_out);
  launch_1d(ray_grad_, size_t(n));
}

}  // namespace sgnlf::render
