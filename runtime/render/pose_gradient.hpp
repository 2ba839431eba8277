// Gradient of a frame's pose correction from its rays' gradients (method.md §0, Poses).
// T = T_init · [Exp_SO3(ω) | u], i.e. R = R_init Exp(ω), t = R_init u + t_init (no left
// Jacobian). Rays given in the LiDAR frame (origins p_r, unit directions v_r) map to
// o_r = R p_r + t, d_r = R v_r. With the right Jacobian J_r of SO(3),
// Exp(ω + δ) ≈ Exp(ω) Exp(J_r(ω) δ), so d(R q)/dω = −R [q]× J_r(ω) and
//   dL/dω = J_r(ω)ᵀ Σ_r (p_r × Rᵀ g_o,r + v_r × Rᵀ g_d,r),   dL/du = R_initᵀ Σ_r g_o,r
// exactly at the current ω (not only at ω = 0). Sums in double, in ray order. corrected_pose()
// and right_jacobian_so3() live in geometry/se3.hpp.
#pragma once
#include <vector>

#include "geometry/se3.hpp"

namespace sgnlf::render {

// dL/dξ = (dL/dω, dL/du). origins_lidar may be empty (all rays start at the sensor origin);
// otherwise every array is n x 3 floats.
Vec6 pose_gradient(const Pose& T_init, const Vec6& xi, const std::vector<float>& origins_lidar,
                   const std::vector<float>& dirs_lidar, const std::vector<float>& grad_o,
                   const std::vector<float>& grad_d);

// The same gradient for rays from the sensor origin, from their sums in the world frame
// (render::PoseGradSums on the device): sum_go = Σ_r g_o,r, sum_cross = Σ_r d_r × g_d,r with
// d_r = R v_r the world directions, so Σ_r v_r × Rᵀ g_d,r = Rᵀ sum_cross:
//   dL/dω = J_r(ω)ᵀ Rᵀ sum_cross,   dL/du = R_initᵀ sum_go   (R = R_init Exp(ω), in double).
Vec6 pose_gradient_from_world_sums(const Pose& T_init, const Vec6& xi, const Vec3& sum_go,
                                   const Vec3& sum_cross);

}  // namespace sgnlf::render
