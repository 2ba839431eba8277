// Chamfer distance and F-score (protocol §4) with one k-d tree per side.
#include "metrics/chamfer.hpp"

#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace sgnlf::metrics {
namespace {

// Mean of the squared distances (in double) and the fraction below the threshold.
void summarize(const std::vector<float>& d, double threshold_sq, double& mean, double& frac) {
  double sum = 0.0;
  size_t below = 0;
  for (float v : d) {
    sum += v;
    // For τ = 0.05 this equals torch's float32 comparison (d < 0.05f): no float lies in
    // [0.05, float(0.05)).
    if (double(v) < threshold_sq) ++below;
  }
  mean = sum / double(d.size());
  frac = double(below) / double(d.size());
}

}  // namespace

NearestSquaredDistances nearest_squared_distances(const std::vector<geometry::Point3f>& pred,
                                                  const std::vector<geometry::Point3f>& gt) {
  require(!pred.empty() && !gt.empty(),
          "nearest_squared_distances: " + std::to_string(pred.size()) + " predicted and " +
              std::to_string(gt.size()) + " ground-truth points; both must be non-empty");
  const geometry::KdTree tree_gt(gt), tree_pred(pred);
  NearestSquaredDistances d;
  tree_gt.nearest_all(pred, d.pred_to_gt);
  tree_pred.nearest_all(gt, d.gt_to_pred);
  return d;
}

ChamferResult chamfer_fscore(const std::vector<geometry::Point3f>& pred,
                             const std::vector<geometry::Point3f>& gt,
                             double threshold_sq) {
  require(threshold_sq > 0.0 && std::isfinite(threshold_sq),
          "chamfer_fscore: threshold_sq must be > 0, got " + std::to_string(threshold_sq));
  ChamferResult r;
  r.n_pred = pred.size();
  r.n_gt = gt.size();
  if (pred.empty() || gt.empty()) {
    // The peers' code would average an empty tensor (NaN); F-score is 0 where undefined.
    r.cd = r.cd_pred_to_gt = r.cd_gt_to_pred = std::numeric_limits<double>::quiet_NaN();
    return r;
  }
  const NearestSquaredDistances d = nearest_squared_distances(pred, gt);
  summarize(d.pred_to_gt, threshold_sq, r.cd_pred_to_gt, r.precision);
  summarize(d.gt_to_pred, threshold_sq, r.cd_gt_to_pred, r.recall);
  r.cd = r.cd_pred_to_gt + r.cd_gt_to_pred;
  const double s = r.precision + r.recall;
  r.fscore = s > 0.0 ? 2.0 * r.precision * r.recall / s : 0.0;
  return r;
}

}  // namespace sgnlf::metrics
