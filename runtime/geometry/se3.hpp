// SE(3)/SO(3) on Eigen. Frames are explicit in names: T_world_lidar maps lidar-frame points
// into the world frame (p_world = T_world_lidar * p_lidar).
#pragma once
#include <Eigen/Geometry>

namespace sgnlf {

using Pose = Eigen::Isometry3d;
using Vec3 = Eigen::Vector3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;  // (ω rotation vector, u translation)
using Mat3 = Eigen::Matrix3d;

Mat3 hat(const Vec3& w);
Mat3 exp_so3(const Vec3& w);  // Rodrigues
Vec3 log_so3(const Mat3& R);  // rotation vector, |ω| ≤ π

// The pose-free methods' parameterisation (method.md §0): [Exp_SO3(ω) | u], the translation
// used directly, without the left Jacobian.
Pose exp_se3_decoupled(const Vec6& xi);
// The corrected pose T_init · [Exp(ω) | u] of that parameterisation: R = R_init Exp(ω),
// t = R_init u + t_init.
Pose corrected_pose(const Pose& T_init, const Vec6& xi);
// Right Jacobian of SO(3) at ω: Exp(ω + δ) ≈ Exp(ω) Exp(J_r(ω) δ) for small δ.
Mat3 right_jacobian_so3(const Vec3& w);
// Full SE(3) exponential/logarithm with the left Jacobian (for metrics and tests).
Pose exp_se3(const Vec6& xi);
Vec6 log_se3(const Pose& T);

// Rotation angle of R in radians (numerically safe arccos((tr R − 1)/2)).
double rotation_angle(const Mat3& R);

// Pose from the 12 row-major numbers of a 3×4 matrix (KITTI files) and back.
Pose pose_from_3x4(const double* v12);
void pose_to_3x4(const Pose& T, double* v12);

}  // namespace sgnlf
