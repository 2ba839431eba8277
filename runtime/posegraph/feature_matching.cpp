// Mutual feature nearest neighbours within a spatial radius (see feature_matching.hpp).
#include "posegraph/feature_matching.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "posegraph/point_features.hpp"

namespace sgnlf::posegraph {
namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

// For every active query point of Q, its feature nearest neighbour among the active points of
// P within the radius (kNone when there is none).
std::vector<uint32_t> best_partners(const FeatureCloud& Q, const FeatureCloud& P, float radius,
                                    const std::vector<uint8_t>& q_active,
                                    const std::vector<uint8_t>& p_active) {
  std::vector<uint32_t> best(Q.size(), kNone);
  std::vector<uint32_t> near;
  for (uint32_t q = 0; q < Q.size(); ++q) {
    if (!q_active.empty() && !q_active[q]) continue;
    P.tree.radius_search(Q.x[q], radius, near);  // ascending indices: ties keep the lowest
    float best_cos = -std::numeric_limits<float>::infinity();
    for (uint32_t p : near) {
      if (!p_active.empty() && !p_active[p]) continue;
      const float c = cosine(Q.row(q), P.row(p), Q.dim);
      if (c > best_cos) {
        best_cos = c;
        best[q] = p;
      }
    }
  }
  return best;
}

}  // namespace

FeatureCloud::FeatureCloud(std::vector<geometry::Point3f> x_common,
                           std::vector<float> unit_features, int d)
    : x(std::move(x_common)), tree(x), features(std::move(unit_features)), dim(d) {
  require(dim >= 1, "FeatureCloud: feature dim " + std::to_string(dim) + " (must be >= 1)");
  require(features.size() == x.size() * size_t(dim),
          "FeatureCloud: " + std::to_string(features.size()) + " feature values for " +
              std::to_string(x.size()) + " points of dim " + std::to_string(dim));
}

std::vector<FeatureMatch> mutual_feature_matches(const FeatureCloud& A, const FeatureCloud& B,
                                                 float radius,
                                                 const std::vector<uint8_t>& a_active,
                                                 const std::vector<uint8_t>& b_active) {
  require(A.dim == B.dim, "mutual_feature_matches: feature dims differ (" +
                              std::to_string(A.dim) + " vs " + std::to_string(B.dim) + ")");
  require(a_active.empty() || a_active.size() == A.size(),
          "mutual_feature_matches: mask of A has " + std::to_string(a_active.size()) +
              " entries for " + std::to_string(A.size()) + " points");
  require(b_active.empty() || b_active.size() == B.size(),
          "mutual_feature_matches: mask of B has " + std::to_string(b_active.size()) +
              " entries for " + std::to_string(B.size()) + " points");
  require(std::isfinite(radius) && radius >= 0.f,
          "mutual_feature_matches: radius " + std::to_string(radius) +
              " (must be finite and >= 0)");
  std::vector<FeatureMatch> out;
  if (A.size() == 0 || B.size() == 0) return out;
  const auto a_to_b = best_partners(A, B, radius, a_active, b_active);
  const auto b_to_a = best_partners(B, A, radius, b_active, a_active);
  for (uint32_t a = 0; a < A.size(); ++a) {
    const uint32_t b = a_to_b[a];
    if (b != kNone && b_to_a[b] == a) out.push_back(FeatureMatch{a, b, cosine(A.row(a), B.row(b), A.dim)});
  }
  return out;
}

}  // namespace sgnlf::posegraph
