// Chamfer distance and F-score between two point sets (protocol §4), as the peers' released
// code computes them (LiDAR4D / GeoNLF utils/metrics.py, chamfer_3DDist):
//   d1 = squared NN distance pred → gt, d2 = gt → pred,
//   CD = mean(d1) + mean(d2)  (a sum of the two directions, in m²),
//   P1 = frac(d1 < τ), P2 = frac(d2 < τ), F = 2·P1·P2 / (P1 + P2), 0 where undefined.
// τ = 0.05 is compared with SQUARED distances, so the effective threshold is √0.05 ≈ 0.2236 m
// (not the "5 cm" some papers state).
#pragma once
#include <vector>

#include "geometry/kdtree.hpp"

namespace sgnlf::metrics {

constexpr double kFscoreThresholdSq = 0.05;  // m², protocol §4

struct ChamferResult {
  double cd = 0.0;           // mean(d1) + mean(d2), m²; NaN when either set is empty
  double cd_pred_to_gt = 0.0;  // mean(d1): accuracy (floaters, mixed edge depths raise it)
  double cd_gt_to_pred = 0.0;  // mean(d2): completeness (holes, missed returns raise it)
  double fscore = 0.0;       // 0 where undefined (P1 + P2 = 0 or an empty set)
  double precision = 0.0;    // P1: fraction of predicted points with d1 < τ
  double recall = 0.0;       // P2: fraction of ground-truth points with d2 < τ
  size_t n_pred = 0, n_gt = 0;
};

// Every point's squared NN distance to the other set (float, as the peers' kernel): d1 per
// predicted point (pred → gt), d2 per ground-truth point (gt → pred). Both sets non-empty.
struct NearestSquaredDistances {
  std::vector<float> pred_to_gt, gt_to_pred;
};
NearestSquaredDistances nearest_squared_distances(const std::vector<geometry::Point3f>& pred,
                                                  const std::vector<geometry::Point3f>& gt);

ChamferResult chamfer_fscore(const std::vector<geometry::Point3f>& pred,
                             const std::vector<geometry::Point3f>& gt,
                             double threshold_sq = kFscoreThresholdSq);

}  // namespace sgnlf::metrics
