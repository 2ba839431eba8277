// SG-NLF's confidence-aware pose graph (method.md §4.2), device-free: given the frames' clouds,
// the current poses T_world_lidar and a feature provider (f_hyb on the device in the pipeline,
// a stand-in in tests), build the weighted edge list of L_graph = Σ α^ij · CD^ij:
//  1. candidate pairs: sequential pairs plus pairs within candidate_distance_m (candidate_pairs);
//  2. per frame: match_points of its cloud in the world, their unit features, voxel grid;
//  3. per candidate: coarse-to-fine mutual feature nearest neighbours (pair_matching.hpp);
//     E^ij = mean cosine similarity of the fine matches, α^ij = mean P_mn over match pairs
//     (spatial_consistency.hpp, on the points in their own LiDAR frames);
//     A pair is valid with enough matches (min_matches and min_match_fraction of its frames'
//     match points: the overlap the matches cover);
//  4. threshold = mean + κ·std of E over the valid sequential pairs;
//  5. edges: every sequential pair (weight α, or, when it is not valid, the mean α of the valid
//     sequential pairs), then the valid non-adjacent pairs with E ≥ threshold (weight α), in
//     (i, j) order. GraphLoss(clouds, graph.edges) is L_graph.
// Deterministic: the same inputs give a bit-identical graph for any thread count (pairs are
// matched into their own slots; the provider is called on the calling thread, once per frame,
// in frame order).
#pragma once
#include <vector>

#include "core/config_fwd.hpp"
#include "geometry/se3.hpp"
#include "posegraph/confidence_graph_config.hpp"
#include "posegraph/edges.hpp"
#include "posegraph/frame_cloud.hpp"
#include "posegraph/point_features.hpp"

namespace sgnlf::posegraph {

struct PairReport {
  int i = 0, j = 0;
  bool sequential = false;
  double centre_distance_m = 0.0;  // under the poses given
  size_t coarse_matches = 0;
  size_t matches = 0;        // fine matches
  double compatibility = 0;  // E^ij (0 without matches)
  double alpha = 0;          // α^ij (0 with < 2 matches)
  bool valid = false;        // enough matches (min_matches, min_match_fraction)
  bool kept = false;         // an edge of the graph
  double weight = 0;         // its weight when kept
};

struct ConfidenceGraph {
  std::vector<Edge> edges;          // for GraphLoss
  std::vector<PairReport> pairs;    // every candidate, (i, j) order
  double threshold = 0.0;           // mean + κ·std (+∞ when no sequential pair is valid)
  double sequential_mean = 0.0, sequential_std = 0.0;
  size_t frames = 0;
  size_t non_adjacent_edges() const;
};

// Throws sgnlf::Error for clouds/poses of different counts, fewer than two frames or a
// non-finite pose; ConfigError for an invalid config; what unit_features throws for a bad
// provider.
ConfidenceGraph build_confidence_graph(const std::vector<FrameCloud>& clouds,
                                       const std::vector<Pose>& T_world_lidar,
                                       const FeatureProvider& features,
                                       const ConfidenceGraphConfig& cfg);

// {"frames", "threshold", "sequential_mean", "sequential_std", "non_adjacent_edges",
//  "edges": [{"i", "j", "sequential", "E", "alpha", "weight", "n_matches", "coarse_matches",
//             "centre_distance_m", "valid", "kept"} for every candidate pair]}
// (threshold null when infinite).
Json confidence_graph_json(const ConfidenceGraph& g);

}  // namespace sgnlf::posegraph
