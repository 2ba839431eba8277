// One direction of GeoNLF's robust Chamfer term (method.md §3) and its analytic pose gradient.
// Direction src→dst: every point p of src goes to q = T_world_dst⁻¹·T_world_src·p (dst's LiDAR
// frame), n = its nearest neighbour in dst's tree, d = |q − n|, d_c = max(d, min_distance),
//   w = softmax over the points of (τ / d_c),      loss = Σ_k w_k · d_k².
// Reading chosen: d² uses the UNCLAMPED d (with d_c² every point closer than 0.15 m would have
// a zero gradient); the clamp acts only inside the weights. τ = 0 gives uniform weights 1/N, the
// plain mean squared nearest-neighbour distance.
// The weights are constants for the gradient (stop-gradient, as GeoNLF detaches them), and so are
// the nearest-neighbour indices (the usual Chamfer gradient, exact between match changes).
// Gradients are with respect to each pose's right rotation perturbation θ (R·Exp(θ)) and its
// world translation t: PoseGrad = (dL/dθ, dL/dt). posegraph/pose_adam.hpp maps them to (ω, u).
// Sums in double, in point order.
#pragma once
#include <cstdint>
#include <vector>

#include "geometry/se3.hpp"
#include "posegraph/frame_cloud.hpp"

namespace sgnlf::posegraph {

using PoseGrad = Vec6;  // (dL/dθ right-perturbation rotation, dL/dt world translation)

struct RobustParams {
  double tau = 0.0;            // softmax temperature numerator (tau_scale · progress)
  double min_distance = 0.15;  // m, clamp of d inside the weights
  // m; > 0: a point whose nearest neighbour is farther has weight 0 (the softmax runs over the
  // others; all weights 0 when no point is that close), the maximum correspondence distance of
  // ICP. Two frames that overlap in part (a non-adjacent pair) otherwise pull together through
  // the points that have no counterpart. 0: every point counts (GeoNLF's robust Chamfer).
  double max_distance = 0.0;
};

struct Match {
  uint32_t dst_index = 0;  // nearest point of dst (input order)
  double sq_distance = 0;  // |q − n|² in double (q in double, n as stored)
};

struct DirectionTerm {
  double loss = 0.0;  // Σ w·d², m²
  PoseGrad grad_src = PoseGrad::Zero(), grad_dst = PoseGrad::Zero();
  size_t points = 0;
};

// Sums one direction term's pose gradients from per-point g = dL/dq (q the src point in dst's
// frame): dL/dθ_src = Σ p × R_dsᵀg, dL/dt_src = R_dst Σ g, dL/dθ_dst = −Σ l × g,
// dL/dt_dst = −R_dst Σ g, with l the dst-frame point whose cross product the term needs (its
// match for point-to-point, where q × g = n × g; q for point-to-plane). Shared by both terms.
class DirectionGradient {
 public:
  explicit DirectionGradient(const Pose& T_dst_src) : R_sd_(T_dst_src.linear().transpose()) {}
  void add(const Vec3& p_src, const Vec3& lever_dst, const Vec3& g) {
    sum_g_ += g;
    rot_src_ += p_src.cross(R_sd_ * g);
    rot_dst_ -= lever_dst.cross(g);
  }
  void write(const Pose& T_world_dst, DirectionTerm& t) const {
    const Vec3 g_world = T_world_dst.linear() * sum_g_;
    t.grad_src << rot_src_, g_world;
    t.grad_dst << rot_dst_, -g_world;
  }

 private:
  Mat3 R_sd_;
  Vec3 sum_g_ = Vec3::Zero(), rot_src_ = Vec3::Zero(), rot_dst_ = Vec3::Zero();
};

// Nearest neighbour in dst of every src point under T_dst_src (query rounded to float, the
// tree's precision; ties go to the lowest dst index).
std::vector<Match> match_direction(const FrameCloud& src, const FrameCloud& dst,
                                   const Pose& T_dst_src);

// softmax_k(τ / max(√sq_distance_k, min_distance)) over the matches within max_distance (all
// when it is 0); sums to 1, or to 0 when no match is within max_distance.
std::vector<double> robust_weights(const std::vector<Match>& matches, const RobustParams& p);

// Σ w·d² and its gradient with matches and weights held fixed.
DirectionTerm weighted_direction(const FrameCloud& src, const FrameCloud& dst,
                                 const Pose& T_world_src, const Pose& T_world_dst,
                                 const std::vector<Match>& matches,
                                 const std::vector<double>& weights);

// match_direction + robust_weights + weighted_direction.
DirectionTerm robust_chamfer_direction(const FrameCloud& src, const FrameCloud& dst,
                                       const Pose& T_world_src, const Pose& T_world_dst,
                                       const RobustParams& p);

}  // namespace sgnlf::posegraph
