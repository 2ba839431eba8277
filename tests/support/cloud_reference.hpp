// Nearest-neighbour references shared by the k-d tree, Chamfer and pose-graph tests: exhaustive
// search with the tree's own float distance, and random flat-ish clouds from the project's Rng.
#pragma once
#include <algorithm>
#include <limits>
#include <vector>

#include "core/rng.hpp"
#include "geometry/kdtree.hpp"

namespace sgnlf::test {

inline float brute_nearest(const std::vector<geometry::Point3f>& pts, const geometry::Point3f& q) {
  float best = std::numeric_limits<float>::infinity();
  for (const auto& p : pts) best = std::min(best, geometry::squared_distance(q, p));
  return best;
}

inline std::vector<geometry::Point3f> random_cloud(Rng& rng, size_t n, float extent) {
  std::vector<geometry::Point3f> pts(n);
  for (auto& p : pts)
    p = geometry::Point3f(rng.uniform(-extent, extent), rng.uniform(-extent, extent),
                          rng.uniform(-extent * 0.1f, extent * 0.1f));
  return pts;
}

}  // namespace sgnlf::test
