// Candidate frame pairs of the confidence-aware pose graph, pruned by distance under the
// current poses so that their number grows with the frames a sensor position has nearby, not
// with all n(n−1)/2 pairs: every sequential pair (i, i + o) for o in the sequential offsets, plus
// every other pair whose sensor positions (the translations of T_world_lidar) lie within
// max_centre_distance_m and whose indices differ by at least min_index_gap (loop-closure
// candidates only, when the gap is large). Found with a k-d tree radius search over the
// positions: O(n log n + pairs).
#pragma once
#include <vector>

#include "geometry/se3.hpp"

namespace sgnlf::posegraph {

struct CandidatePair {
  int i = 0, j = 0;  // i < j
  bool sequential = false;
  double centre_distance_m = 0.0;
};

// Sorted by (i, j). Throws sgnlf::Error for a non-finite pose, an offset < 1 or a negative or
// non-finite distance.
std::vector<CandidatePair> candidate_pairs(const std::vector<Pose>& T_world_lidar,
                                           const std::vector<int>& sequential_offsets,
                                           double max_centre_distance_m, int min_index_gap = 0);

}  // namespace sgnlf::posegraph
