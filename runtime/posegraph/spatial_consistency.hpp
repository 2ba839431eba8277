// Spatial consistency of a correspondence set (method.md §4.2): for two matches m = (p_m, q_m)
// and n = (p_n, q_n), p in frame i and q in frame j (each in any one rigid frame of its own:
// the distances do not depend on the poses),
//   P_mn = exp(−(‖p_m − p_n‖ − ‖q_m − q_n‖)² / (2σ_d²)),
// and the edge weight α^ij = mean of P_mn over the pairs m < n. Correct matches of a rigid scene
// keep every distance (P ≈ 1); a wrong match breaks its distances to all others. With more than
// max_pairs pairs, α is the mean over max_pairs pairs drawn (with replacement, m ≠ n) from
// Rng(seed, stream): deterministic for given inputs. α is a constant of the pose-graph loss
// (like GeoNLF's robust weights it carries no gradient).
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/se3.hpp"

namespace sgnlf::posegraph {

inline double pair_consistency(const Vec3& p_m, const Vec3& p_n, const Vec3& q_m,
                               const Vec3& q_n, double sigma_d) {
  const double r = (p_m - p_n).norm() - (q_m - q_n).norm();
  return std::exp(-r * r / (2.0 * sigma_d * sigma_d));
}

// α over the matches (p[k], q[k]). 0 with fewer than two matches. Throws sgnlf::Error when p and
// q differ in size, sigma_d ≤ 0 or max_pairs = 0.
double spatial_consistency(const std::vector<Vec3>& p, const std::vector<Vec3>& q,
                           double sigma_d, size_t max_pairs, uint64_t seed, uint32_t stream);

}  // namespace sgnlf::posegraph
