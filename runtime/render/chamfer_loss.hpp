// Chamfer losses with their gradients for training LiDAR4D (method.md §2; LiDAR4D
// model/runner.py): the symmetric Chamfer term between two point sets with its gradient with
// respect to the first (nearest neighbours held fixed, the usual Chamfer gradient, exact
// between match changes), and its use on ray points: predicted endpoints o + d·depth against
// the observed ones of the same rays. Nearest neighbours come from geometry::KdTree, the exact
// search that metrics/chamfer.hpp (evaluation) and the pose graph use; distances are squared,
// as in metrics::chamfer_fscore. Host code: the point sets are small (one batch, one frame).
#pragma once
#include <vector>

#include "geometry/kdtree.hpp"

namespace sgnlf::render {

using geometry::Point3f;

enum class ChamferReduce { Mean, Sum };

struct ChamferLoss {
  double loss = 0.0;             // 0.5 · (R_i d1_i + R_j d2_j), R = mean or sum
  std::vector<Point3f> d_pred;   // dL/dpred, one per predicted point
};

// d1_i = min_j |pred_i − target_j|², d2_j = min_i |pred_i − target_j|². Empty sets give a
// zero loss and gradient (a missing neighbour frame contributes nothing).
ChamferLoss chamfer_loss(const std::vector<Point3f>& pred, const std::vector<Point3f>& target,
                         ChamferReduce reduce);

struct RayChamferLoss {
  double loss = 0.0;
  std::vector<float> d_depth;  // dL/d(predicted depth), one per ray
};

// LiDAR4D's Chamfer term on a batch of rays of one frame: pred_i = dir_i · depth_i / scale,
// target_i = dir_i · gt_depth_i / scale (rays without a return carry depth 0 in both, as
// LiDAR4D masks them), mean reduction, times `weight`. dir is N × 3.
RayChamferLoss ray_chamfer_loss(const std::vector<float>& dir, const std::vector<float>& depth,
                                const std::vector<float>& gt_depth, float scale,
                                float weight = 1.0f);

}  // namespace sgnlf::render
