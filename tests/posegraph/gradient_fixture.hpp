// Test fixture shared by the direction terms' gradient tests: two base poses with corrections
// ξ, central differences over the 12 parameters (ξ_0, ξ_1), and the symmetric relative error.
#pragma once
#include <algorithm>

#include <Eigen/Core>

#include "geometry/se3.hpp"

namespace sgnlf::test {

const Pose kBase0 = exp_se3((Vec6() << 0.05, -0.02, 0.3, 1.0, -0.5, 0.2).finished());
const Pose kBase1 = exp_se3((Vec6() << -0.03, 0.04, 0.5, 3.0, 0.8, -0.1).finished());
const Vec6 kXi0 = (Vec6() << 0.02, -0.03, 0.25, 0.3, -0.2, 0.1).finished();
const Vec6 kXi1 = (Vec6() << -0.04, 0.01, -0.3, -0.2, 0.4, 0.05).finished();

// ‖a − n‖ / max(‖a‖, ‖n‖): 0 for equal vectors, 2 for a = −n.
inline double sym_rel_error(const Eigen::VectorXd& a, const Eigen::VectorXd& n) {
  return (a - n).norm() / std::max({a.norm(), n.norm(), 1e-300});
}

// f(ξ_0, ξ_1) differentiated over the 12 parameters by central differences with step h.
template <class F>
Eigen::VectorXd central_differences(F f, double h) {
  Eigen::VectorXd g(12);
  for (int k = 0; k < 12; ++k) {
    Vec6 p0 = kXi0, p1 = kXi1, m0 = kXi0, m1 = kXi1;
    (k < 6 ? p0 : p1)[k % 6] += h;
    (k < 6 ? m0 : m1)[k % 6] -= h;
    g[k] = (f(p0, p1) - f(m0, m1)) / (2 * h);
  }
  return g;
}

inline Eigen::VectorXd stack(const Vec6& a, const Vec6& b) {
  Eigen::VectorXd g(12);
  g << a, b;
  return g;
}

}  // namespace sgnlf::test
