// The Gauss-Newton normal equations of point-to-point ICP (KISS-ICP eq. 7–8) for the left
// perturbation T ← Exp(δ)·T, δ = (ω, u), kept as the sums they are made of. With
// J = [−p^, I] (∂(Exp(δ)p)/∂δ at δ = 0):
//   JᵀJ = [[|p|²I − ppᵀ, p^], [−p^, I]],  Jᵀr = [p × r; r],
// so Σ w JᵀJ needs only Σ w(|p|²I − ppᵀ), Σ w p and Σ w: ~30 flops a correspondence instead
// of the ~250 of the dense 6 × 6 product (after the map search, the ICP's largest cost).
// Tests compare it with the dense sums.
#pragma once
#include <Eigen/Core>
#include <cstddef>

#include "geometry/se3.hpp"

namespace sgnlf::odometry {

struct NormalEquations {
  Mat3 rot = Mat3::Zero();  // Σ w (|p|²I − ppᵀ)
  Vec3 wp = Vec3::Zero();   // Σ w p
  double w = 0.0;           // Σ w
  Vec6 JTr = Vec6::Zero();  // Σ w Jᵀr = Σ w [p × r; r]
  size_t count = 0;         // correspondences
  double sse = 0.0;         // Σ |r|² (unweighted)

  // One correspondence: the transformed source point p, its residual r = p − q, weight w.
  void add_point(const Vec3& p, const Vec3& r, double weight) {
    const Vec3 wpi = weight * p;
    rot.noalias() -= wpi * p.transpose();
    rot.diagonal().array() += wpi.dot(p);
    wp += wpi;
    w += weight;
    JTr.head<3>() += wpi.cross(r);
    JTr.tail<3>() += weight * r;
  }
  // Counts a correspondence for fitness and RMSE only.
  void count_point(double squared_distance) {
    ++count;
    sse += squared_distance;
  }
  void add(const NormalEquations& o);
  // Σ w JᵀJ.
  Eigen::Matrix<double, 6, 6> JTJ() const;
};

}  // namespace sgnlf::odometry
