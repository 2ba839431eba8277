// LiDAR4D's Chamfer term on the device (device profile chamfer: device; kernels/render/
// chamfer.cl): render::chamfer_loss (render/chamfer_loss.hpp) with exact brute-force nearest
// neighbours in local-memory tiles instead of geometry::KdTree, its gradient w.r.t. the
// predicted points (neighbours held fixed) and its value summed in a fixed tree, all enqueued:
// nothing is read back. ray() is render::ray_chamfer_loss on the model's batch buffers.
// Deterministic on one device; against the host the neighbours are the same where the device
// rounds distances as IEEE float does (ties to the lowest index, as the k-d tree), the loss
// differs by its float sums' rounding (the host sums in double).
#pragma once
#include <string>

#include "cl/runtime.hpp"
#include "render/chamfer_loss.hpp"

namespace sgnlf::render {

// Where the gradient goes: out[stride·i + offset + k] (+)= mul · dL/dpred_i[k].
struct ChamferGradOut {
  cl::Buffer* out = nullptr;
  int stride = 3, offset = 0;
  float mul = 1.0f;
  bool accumulate = false;
};

// The build options of kernels/render/chamfer.cl (its tile sizes), one program for all of it.
std::string chamfer_program_options();

class DeviceChamfer {
 public:
  explicit DeviceChamfer(cl::Runtime& rt);

  // L = loss_scale · 0.5 · (R Σ_i d1_i + R Σ_j d2_j), R = 1/n (mean) or 1 (sum), of pred
  // (n_pred × 3) and target (n_target × 3) into loss[slot]; dL/dpred (with loss_scale = 1)
  // into `grad`. An empty set gives 0 and a zero gradient (written, or nothing added).
  void run(const cl::Buffer& pred, int n_pred, const cl::Buffer& target, int n_target,
           ChamferReduce reduce, float loss_scale, const ChamferGradOut& grad, cl::Buffer& loss,
           int slot);

  // render::ray_chamfer_loss of n rays: directions dir (n × 3), depths out[3i], observed
  // ranges target[3i] and labels target[3i + 2] (the model's output and target buffers),
  // weight · dL/d(depth) added to grad_out[3i] of the rays with a return; its value into
  // loss[slot].
  void ray(const cl::Buffer& dir, const cl::Buffer& out, const cl::Buffer& target, int n,
           float scale, float weight, cl::Buffer& grad_out, cl::Buffer& loss, int slot);

  // Sums a (n1) and b (n2) into loss[slot] = c1·Σa + c2·Σb in the fixed tree.
  void sum(int n1, const cl::Buffer& a, float c1, int n2, const cl::Buffer& b, float c2,
           cl::Buffer& loss, int slot);

 private:
  cl::Runtime& rt_;
  cl::Kernel nearest_, grad_, sum_, ray_points_, ray_grad_;
  cl::Buffer nn1_, nn2_, d1_, d2_;             // per point of pred, of target
  cl::Buffer ray_pred_, ray_target_, ray_g_;  // ray(): the endpoints and dL/dpred
  size_t cap1_ = 0, cap2_ = 0, ray_cap_ = 0;
  void ensure(int n_pred, int n_target);
};

}  // namespace sgnlf::render
