// Mutual nearest neighbours in feature space, restricted to a spatial search radius
// (method.md §4.2, the correspondence step of the confidence-aware pose graph). Both sides are
// given in one common frame (the world under the current poses). For a point a of A, its
// candidate partners are the points b of B with ‖x_a − x_b‖ ≤ radius (float, as the k-d tree
// tests it); its feature nearest neighbour is the candidate of largest cosine similarity (ties:
// lowest index). (a, b) is a match when each is the other's feature nearest neighbour.
#pragma once
#include <cstdint>
#include <vector>

#include "geometry/kdtree.hpp"

namespace sgnlf::posegraph {

// One side of a match: points, their k-d tree (built once here) and unit feature rows.
struct FeatureCloud {
  std::vector<geometry::Point3f> x;  // common frame (world), metres
  geometry::KdTree tree;             // over x
  std::vector<float> features;       // x.size() × dim, unit rows (point_features.hpp)
  int dim = 0;

  // Throws sgnlf::Error when features.size() != x.size() · dim or dim < 1.
  FeatureCloud(std::vector<geometry::Point3f> x_common, std::vector<float> unit_features,
               int dim);
  size_t size() const { return x.size(); }
  const float* row(uint32_t k) const { return features.data() + size_t(k) * size_t(dim); }
};

struct FeatureMatch {
  uint32_t a = 0, b = 0;  // indices into A and B
  float cosine = 0.f;     // cosine similarity of their features
};

// Mutual matches in increasing order of a. `a_active` / `b_active` (empty = all points) restrict
// both the queries and the partners to the flagged points (the fine level of coarse-to-fine
// matching). Throws sgnlf::Error for different feature dims, masks of the wrong size or a radius
// that is negative or not finite.
std::vector<FeatureMatch> mutual_feature_matches(const FeatureCloud& A, const FeatureCloud& B,
                                                 float radius,
                                                 const std::vector<uint8_t>& a_active = {},
                                                 const std::vector<uint8_t>& b_active = {});

}  // namespace sgnlf::posegraph
