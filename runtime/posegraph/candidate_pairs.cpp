// candidate_pairs (see candidate_pairs.hpp).
#include "posegraph/candidate_pairs.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "core/error.hpp"
#include "geometry/kdtree.hpp"

namespace sgnlf::posegraph {

std::vector<CandidatePair> candidate_pairs(const std::vector<Pose>& T,
                                           const std::vector<int>& sequential_offsets,
                                           double max_distance, int min_index_gap) {
  require(std::isfinite(max_distance) && max_distance >= 0.0,
          "candidate_pairs: distance " + std::to_string(max_distance) + " m (must be >= 0)");
  const int n = int(T.size());
  std::set<int> offsets;
  for (int o : sequential_offsets) {
    require(o >= 1, "candidate_pairs: sequential offset " + std::to_string(o) + " (must be >= 1)");
    offsets.insert(o);
  }
  std::vector<geometry::Point3f> centres;
  for (int k = 0; k < n; ++k) {
    require(T[size_t(k)].matrix().allFinite(),
            "candidate_pairs: pose of frame " + std::to_string(k) + " is not finite");
    centres.push_back(T[size_t(k)].translation().cast<float>());
  }
  std::vector<CandidatePair> out;
  auto add = [&](int i, int j, bool seq) {
    const double d = (T[size_t(i)].translation() - T[size_t(j)].translation()).norm();
    out.push_back(CandidatePair{i, j, seq, d});
  };
  if (n < 2) return out;
  const geometry::KdTree tree(centres, 8);
  std::vector<uint32_t> near;
  for (int i = 0; i < n; ++i) {
    tree.radius_search(centres[size_t(i)], float(max_distance), near);
    // Merge the sequential partners (always kept) with the near ones, both ascending.
    std::set<int> partners;
    for (int o : offsets)
      if (i + o < n) partners.insert(i + o);
    for (uint32_t j : near)
      if (int(j) > i && int(j) - i >= min_index_gap) partners.insert(int(j));
    for (int j : partners) add(i, j, offsets.count(j - i) > 0);
  }
  return out;
}

}  // namespace sgnlf::posegraph
