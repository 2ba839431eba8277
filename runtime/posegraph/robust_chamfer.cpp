// Robust Chamfer direction term (see robust_chamfer.hpp for the formulas and conventions).
#include "posegraph/robust_chamfer.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace sgnlf::posegraph {

std::vector<Match> match_direction(const FrameCloud& src, const FrameCloud& dst,
                                   const Pose& T_dst_src) {
  std::vector<Match> out(src.size());
  for (size_t k = 0; k < src.size(); ++k) {
    const Vec3 q = T_dst_src * src.points[k].cast<double>();
    Match& m = out[k];
    dst.tree.nearest(q.cast<float>(), &m.dst_index);
    m.sq_distance = (q - dst.points[m.dst_index].cast<double>()).squaredNorm();
  }
  return out;
}

std::vector<double> robust_weights(const std::vector<Match>& matches, const RobustParams& p) {
  require(p.min_distance > 0.0 && std::isfinite(p.tau) && p.tau >= 0.0 &&
              std::isfinite(p.max_distance) && p.max_distance >= 0.0,
          "robust_weights: need tau >= 0, min_distance > 0 and max_distance >= 0 (tau " +
              std::to_string(p.tau) + ", min_distance " + std::to_string(p.min_distance) +
              ", max_distance " + std::to_string(p.max_distance) + ")");
  const bool trimmed = p.max_distance > 0.0;
  const double max_sq = p.max_distance * p.max_distance;
  std::vector<double> w(matches.size());
  double top = -1.0;
  for (size_t k = 0; k < w.size(); ++k) {
    w[k] = p.tau / std::max(std::sqrt(matches[k].sq_distance), p.min_distance);
    if (!trimmed || matches[k].sq_distance <= max_sq) top = std::max(top, w[k]);
  }
  double sum = 0.0;
  for (size_t k = 0; k < w.size(); ++k) {
    const bool kept = !trimmed || matches[k].sq_distance <= max_sq;
    sum += (w[k] = kept ? std::exp(w[k] - top) : 0.0);  // shifted: every term ≤ 1, the top = 1
  }
  if (sum > 0.0)
    for (double& v : w) v /= sum;
  return w;
}

DirectionTerm weighted_direction(const FrameCloud& src, const FrameCloud& dst,
                                 const Pose& T_world_src, const Pose& T_world_dst,
                                 const std::vector<Match>& matches,
                                 const std::vector<double>& weights) {
  require(matches.size() == src.size() && weights.size() == src.size(),
          "weighted_direction: " + std::to_string(matches.size()) + " matches and " +
              std::to_string(weights.size()) + " weights for " + std::to_string(src.size()) +
              " points");
  // Residual e = q − n in dst's frame; world residual x − y = R_dst·e, so with
  // g = dL/dx = 2w·R_dst·e:  dL/dt_src = Σ g,  dL/dθ_src = Σ p × R_srcᵀ g = Σ p × R_dsᵀ(2w e),
  // dL/dt_dst = −Σ g,  dL/dθ_dst = −Σ n × R_dstᵀ g = −Σ n × (2w e).
  const Pose T_ds = T_world_dst.inverse() * T_world_src;
  DirectionTerm t;
  t.points = src.size();
  DirectionGradient grad(T_ds);
  for (size_t k = 0; k < src.size(); ++k) {
    const Vec3 p = src.points[k].cast<double>();
    const Vec3 n = dst.points[matches[k].dst_index].cast<double>();
    const Vec3 e = T_ds * p - n;
    t.loss += weights[k] * e.squaredNorm();
    grad.add(p, n, 2.0 * weights[k] * e);
  }
  grad.write(T_world_dst, t);
  return t;
}

DirectionTerm robust_chamfer_direction(const FrameCloud& src, const FrameCloud& dst,
                                       const Pose& T_world_src, const Pose& T_world_dst,
                                       const RobustParams& p) {
  const auto matches = match_direction(src, dst, T_world_dst.inverse() * T_world_src);
  return weighted_direction(src, dst, T_world_src, T_world_dst, matches,
                            robust_weights(matches, p));
}

}  // namespace sgnlf::posegraph
