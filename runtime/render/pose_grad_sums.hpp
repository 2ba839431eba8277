// The pose gradient's reduction on the device (kernels/render/pose_grad.cl; device profile
// pose_grad: device): a frame's per-ray gradients summed into six floats, s_o = Σ g_o,r and
// s_x = Σ d_r × (g_d,r + g_dir,r) in the world frame, in a fixed tree (bit-reproducible on one
// device), read back with one blocking read of 24 bytes instead of the 3 × n_rays × 3 floats
// that render::pose_gradient() takes on the host. pose_gradient_from_world_sums()
// (pose_gradient.hpp) turns them into dL/dξ.
#pragma once
#include "cl/runtime.hpp"
#include "geometry/se3.hpp"

namespace sgnlf::render {

struct RayGradSums {
  Vec3 origin = Vec3::Zero();  // Σ_r dL/do_r
  Vec3 cross = Vec3::Zero();   // Σ_r d_r × dL/dd_r (world frame)
};

class PoseGradSums {
 public:
  explicit PoseGradSums(cl::Runtime& rt);
  // d, g_o, g_d, g_dir: n_rays × 3 floats (world directions, dL/do, dL/dd and the direction
  // encoding's share of dL/dd). Only enqueues.
  void reduce(int n_rays, const cl::Buffer& d, const cl::Buffer& g_o, const cl::Buffer& g_d,
              const cl::Buffer& g_dir);
  // The sums of the last reduce(): one blocking read of 6 floats (or, by a caller that reads
  // them with other values in one transfer, from sums() copied elsewhere: from_floats()).
  RayGradSums read() const;
  const cl::Buffer& sums() const { return out_; }  // 6 floats: s_o, then s_x
  static RayGradSums from_floats(const float* s);

 private:
  cl::Kernel k_;
  cl::Buffer out_;
};

}  // namespace sgnlf::render
