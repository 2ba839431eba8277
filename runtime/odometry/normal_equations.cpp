// NormalEquations (see normal_equations.hpp).
#include "odometry/normal_equations.hpp"

namespace sgnlf::odometry {

void NormalEquations::add(const NormalEquations& o) {
  rot += o.rot;
  wp += o.wp;
  w += o.w;
  JTr += o.JTr;
  count += o.count;
  sse += o.sse;
}

Eigen::Matrix<double, 6, 6> NormalEquations::JTJ() const {
  Eigen::Matrix<double, 6, 6> m;
  m.topLeftCorner<3, 3>() = rot;
  m.topRightCorner<3, 3>() = hat(wp);
  m.bottomLeftCorner<3, 3>() = -hat(wp);
  m.bottomRightCorner<3, 3>() = w * Mat3::Identity();
  return m;
}

}  // namespace sgnlf::odometry
