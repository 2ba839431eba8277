// PoseGradSums: launcher of kernels/render/pose_grad.cl.
#include "render/pose_grad_sums.hpp"

#include "render/launch.hpp"

namespace sgnlf::render {

namespace {
constexpr size_t kWg = 256;  // POSE_GRAD_WG
}

PoseGradSums::PoseGradSums(cl::Runtime& rt)
    : k_(rt.kernel("render/pose_grad.cl", "render_pose_grad_sums",
                   "-DPOSE_GRAD_WG=" + std::to_string(kWg))),
      out_(rt, 6 * sizeof(float)) {}

void PoseGradSums::reduce(int n_rays, const cl::Buffer& d, const cl::Buffer& g_o,
                          const cl::Buffer& g_d, const cl::Buffer& g_dir) {
  require(n_rays >= 0, "PoseGradSums::reduce: negative ray count");
  const size_t n3 = 3 * size_t(n_rays);
  check_floats(d, n3, "PoseGradSums::reduce d");
  check_floats(g_o, n3, "PoseGradSums::reduce g_o");
  check_floats(g_d, n3, "PoseGradSums::reduce g_d");
  check_floats(g_dir, n3, "PoseGradSums::reduce g_dir");
  k_.set_args(n_rays, d, g_o, g_d, g_dir, out_);
  k_.launch({kWg}, {kWg});
}

RayGradSums PoseGradSums::read() const {
  const auto s = out_.read_vec<float>(6);
  return from_floats(s.data());
}

RayGradSums PoseGradSums::from_floats(const float* s) {
  RayGradSums r;
  r.origin = Vec3(s[0], s[1], s[2]);
  r.cross = Vec3(s[3], s[4], s[5]);
  return r;
}

}  // namespace sgnlf::render
