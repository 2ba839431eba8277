#include "geometry/se3.hpp"

#include <algorithm>
#include <cmath>

namespace sgnlf {

Mat3 hat(const Vec3& w) {
  Mat3 m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}

Mat3 exp_so3(const Vec3& w) {
  const double th = w.norm();
  const Mat3 W = hat(w);
  if (th < 1e-8) return Mat3::Identity() + W + 0.5 * W * W;
  return Mat3::Identity() + std::sin(th) / th * W + (1 - std::cos(th)) / (th * th) * W * W;
}

double rotation_angle(const Mat3& R) {
  const double c = std::clamp((R.trace() - 1.0) * 0.5, -1.0, 1.0);
  return std::acos(c);
}

Vec3 log_so3(const Mat3& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

Pose exp_se3_decoupled(const Vec6& xi) {
  Pose T = Pose::Identity();
  T.linear() = exp_so3(xi.head<3>());
  T.translation() = xi.tail<3>();
  return T;
}

Pose corrected_pose(const Pose& T_init, const Vec6& xi) { return T_init * exp_se3_decoupled(xi); }

Mat3 right_jacobian_so3(const Vec3& w) {
  const double th2 = w.squaredNorm();
  const Mat3 W = hat(w);
  double a, b;  // J_r = I − a W + b W²
  if (th2 < 1e-8) {
    a = 0.5 - th2 / 24.0;
    b = 1.0 / 6.0 - th2 / 120.0;
  } else {
    const double th = std::sqrt(th2);
    a = (1.0 - std::cos(th)) / th2;
    b = (th - std::sin(th)) / (th2 * th);
  }
  return Mat3::Identity() - a * W + b * W * W;
}

static Mat3 left_jacobian(const Vec3& w) {
  const double th = w.norm();
  const Mat3 W = hat(w);
  if (th < 1e-8) return Mat3::Identity() + 0.5 * W;
  return Mat3::Identity() + (1 - std::cos(th)) / (th * th) * W +
         (th - std::sin(th)) / (th * th * th) * W * W;
}

Pose exp_se3(const Vec6& xi) {
  Pose T = Pose::Identity();
  T.linear() = exp_so3(xi.head<3>());
  T.translation() = left_jacobian(xi.head<3>()) * xi.tail<3>();
  return T;
}

Vec6 log_se3(const Pose& T) {
  Vec6 xi;
  xi.head<3>() = log_so3(T.linear());
  xi.tail<3>() = left_jacobian(xi.head<3>()).inverse() * T.translation();
  return xi;
}

Pose pose_from_3x4(const double* v) {
  Pose T = Pose::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T.matrix()(r, c) = v[r * 4 + c];
    T.matrix()(r, 3) = v[r * 4 + 3];
  }
  return T;
}

void pose_to_3x4(const Pose& T, double* v) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) v[r * 4 + c] = T.matrix()(r, c);
}

}  // namespace sgnlf
