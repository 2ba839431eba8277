// A point-to-plane direction term for the pose-graph loss (graph_loss.hpp's DirectionFn), the
// alternative to GeoNLF's point-to-point robust Chamfer (robust_chamfer.hpp):
//   loss = Σ_k w_k · (n_kᵀ (q_k − m_k))²,
// q_k the src point in dst's frame, m_k its nearest dst point, n_k that point's normal
// (FrameCloud::normals; zero-normal points contribute nothing), w_k GeoNLF's robust softmax
// weights on the point distances |q_k − m_k| (robust_weights). Why: between two sparse scans
// metres apart (2 Hz keyframes) the nearest neighbour of a ring point lies on another ring, and
// point-to-point pulls the scans together along the ground; the plane residual lets points slide
// along the surface (measured: docs/studies/odometry/pose_free_from_odometry.md). Gradients, as
// robust_chamfer.hpp, with matches and weights held fixed: with r = nᵀe and g = 2w·r·n
// (dL/dq in dst's frame), dL/dθ_src = Σ p × R_dsᵀg, dL/dt_src = R_dst Σ g,
// dL/dθ_dst = −Σ q × g, dL/dt_dst = −R_dst Σ g.
#pragma once
#include "posegraph/robust_chamfer.hpp"

namespace sgnlf::posegraph {

// Throws sgnlf::Error when dst has no normals (make_frame_clouds without NormalOptions).
DirectionTerm weighted_plane_direction(const FrameCloud& src, const FrameCloud& dst,
                                       const Pose& T_world_src, const Pose& T_world_dst,
                                       const std::vector<Match>& matches,
                                       const std::vector<double>& weights);

// match_direction + robust_weights + weighted_plane_direction.
DirectionTerm point_to_plane_direction(const FrameCloud& src, const FrameCloud& dst,
                                       const Pose& T_world_src, const Pose& T_world_dst,
                                       const RobustParams& p);

}  // namespace sgnlf::posegraph
