// Did a pose-free run converge? A check from what a run knows without ground truth: under the estimated poses, every graph edge (i, j) should overlap — a share of frame
// i's points lies within `inlier_distance_m` of frame j's scan. Measured on real nuScenes
// scene-0916 (36 keyframes, 2 Hz, edges (i, i+1), 8000 points, 0.5 m): ground-truth poses give
// 0.68–0.72 on every edge; the protocol's noisy start 0.002–0.3; a run stuck at 1.6 m ATE
// 0.70 on most edges and 0.47 on its broken ones (docs/real-scans.md). So an edge is suspect
// when its overlap falls below `edge_ratio` × the median over the run's edges (relative, so the
// rule holds for any sensor density and frame rate), and the whole trajectory is unconverged
// when the median itself falls below `min_median_overlap` (nothing overlaps anywhere) or any
// edge is suspect. Neighbour jumps (relative motion far from its neighbours') are reported too.
#pragma once
#include <string>
#include <vector>

#include "core/config_fwd.hpp"
#include "geometry/se3.hpp"
#include "posegraph/edges.hpp"
#include "posegraph/frame_cloud.hpp"

namespace sgnlf::posegraph {

struct TrajectoryCheckConfig {
  double inlier_distance_m = 0.5;   // a point overlaps when its nearest neighbour is this close
  double edge_ratio = 0.8;          // suspect edge: overlap < edge_ratio · median overlap
  double min_median_overlap = 0.2;  // below it no edge is trusted (the run did not register)
  double jump_ratio = 4.0;          // jump: |step translation| > jump_ratio · median + 1 m
  void validate() const;            // ConfigError naming the field
};

struct EdgeOverlap {
  int i = 0, j = 0;
  double overlap = 0.0;            // mean of both directions' inlier shares
  double median_distance_m = 0.0;  // mean of both directions' median NN distances
  bool suspect = false;
};

struct TrajectoryCheck {
  bool converged = true;
  double median_overlap = 0.0;
  std::vector<EdgeOverlap> edges;
  std::vector<int> jumps;  // frames k whose step k → k+1 is a jump
  std::string reason;      // empty when converged; else what failed, for a warning line
  int suspect_edges() const;
  Json to_json() const;
};

// Overlap of every edge under T_world_lidar (clouds and poses in the same order).
// Throws sgnlf::Error for a pose count that differs from the clouds' or an invalid edge list.
TrajectoryCheck check_trajectory(const std::vector<FrameCloud>& clouds,
                                 const std::vector<Pose>& T_world_lidar,
                                 const std::vector<Edge>& edges,
                                 const TrajectoryCheckConfig& cfg = {});

}  // namespace sgnlf::posegraph
