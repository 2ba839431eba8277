// Pose gradient from per-ray origin/direction gradients (see pose_gradient.hpp).
#include "render/pose_gradient.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace sgnlf::render {

Vec6 pose_gradient(const Pose& T_init, const Vec6& xi, const std::vector<float>& origins_lidar,
                   const std::vector<float>& dirs_lidar, const std::vector<float>& grad_o,
                   const std::vector<float>& grad_d) {
  const size_t n3 = dirs_lidar.size();
  require(n3 % 3 == 0 && grad_o.size() == n3 && grad_d.size() == n3 &&
              (origins_lidar.empty() || origins_lidar.size() == n3),
          "pose_gradient: arrays must all be n x 3 (dirs " + std::to_string(n3) + ", grad_o " +
              std::to_string(grad_o.size()) + ", grad_d " + std::to_string(grad_d.size()) +
              ", origins " + std::to_string(origins_lidar.size()) + " floats)");
  const Vec3 w = xi.head<3>();
  const Mat3 R = T_init.linear() * exp_so3(w);
  Vec3 sum_go = Vec3::Zero(), sum_rot = Vec3::Zero();
  for (size_t i = 0; i < n3; i += 3) {
    const Vec3 go(grad_o[i], grad_o[i + 1], grad_o[i + 2]);
    const Vec3 gd(grad_d[i], grad_d[i + 1], grad_d[i + 2]);
    const Vec3 v(dirs_lidar[i], dirs_lidar[i + 1], dirs_lidar[i + 2]);
    sum_go += go;
    sum_rot += v.cross(R.transpose() * gd);
    if (!origins_lidar.empty()) {
      const Vec3 p(origins_lidar[i], origins_lidar[i + 1], origins_lidar[i + 2]);
      sum_rot += p.cross(R.transpose() * go);
    }
  }
  Vec6 g;
  g.head<3>() = right_jacobian_so3(w).transpose() * sum_rot;
  g.tail<3>() = T_init.linear().transpose() * sum_go;
  return g;
}

Vec6 pose_gradient_from_world_sums(const Pose& T_init, const Vec6& xi, const Vec3& sum_go,
                                   const Vec3& sum_cross) {
  const Vec3 w = xi.head<3>();
  const Mat3 R = T_init.linear() * exp_so3(w);
  Vec6 g;
  g.head<3>() = right_jacobian_so3(w).transpose() * (R.transpose() * sum_cross);
  g.tail<3>() = T_init.linear().transpose() * sum_go;
  return g;
}

}  // namespace sgnlf::render
