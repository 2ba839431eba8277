// Point-to-plane direction term (see point_to_plane.hpp).
#include "posegraph/point_to_plane.hpp"

#include <string>

#include "core/error.hpp"

namespace sgnlf::posegraph {

DirectionTerm weighted_plane_direction(const FrameCloud& src, const FrameCloud& dst,
                                       const Pose& T_world_src, const Pose& T_world_dst,
                                       const std::vector<Match>& matches,
                                       const std::vector<double>& weights) {
  require(dst.normals.size() == dst.size(),
          "point-to-plane term: the destination cloud has " + std::to_string(dst.normals.size()) +
              " normals for " + std::to_string(dst.size()) + " points (built without normals?)");
  require(matches.size() == src.size() && weights.size() == src.size(),
          "weighted_plane_direction: " + std::to_string(matches.size()) + " matches and " +
              std::to_string(weights.size()) + " weights for " + std::to_string(src.size()) +
              " points");
  const Pose T_ds = T_world_dst.inverse() * T_world_src;
  DirectionTerm t;
  t.points = src.size();
  DirectionGradient grad(T_ds);
  for (size_t k = 0; k < src.size(); ++k) {
    const Vec3 n = dst.normals[matches[k].dst_index].cast<double>();
    if (n.squaredNorm() == 0.0) continue;  // no plane there
    const Vec3 p = src.points[k].cast<double>();
    const Vec3 q = T_ds * p;
    const double r = n.dot(q - dst.points[matches[k].dst_index].cast<double>());
    t.loss += weights[k] * r * r;
    grad.add(p, q, 2.0 * weights[k] * r * n);
  }
  grad.write(T_world_dst, t);
  return t;
}

DirectionTerm point_to_plane_direction(const FrameCloud& src, const FrameCloud& dst,
                                       const Pose& T_world_src, const Pose& T_world_dst,
                                       const RobustParams& p) {
  const auto matches = match_direction(src, dst, T_world_dst.inverse() * T_world_src);
  return weighted_plane_direction(src, dst, T_world_src, T_world_dst, matches,
                                  robust_weights(matches, p));
}

}  // namespace sgnlf::posegraph
