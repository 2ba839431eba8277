// Chamfer losses and gradients (render/chamfer_loss.hpp). Sums in double, in point order.
#include "render/chamfer_loss.hpp"

#include <string>

#include "core/error.hpp"

namespace sgnlf::render {

ChamferLoss chamfer_loss(const std::vector<Point3f>& pred, const std::vector<Point3f>& target,
                         ChamferReduce reduce) {
  ChamferLoss out;
  out.d_pred.assign(pred.size(), Point3f::Zero());
  if (pred.empty() || target.empty()) return out;
  const bool mean = reduce == ChamferReduce::Mean;
  const double s1 = 0.5 / (mean ? double(pred.size()) : 1.0);
  const double s2 = 0.5 / (mean ? double(target.size()) : 1.0);
  const geometry::KdTree to_target(target), to_pred(pred);
  double l1 = 0, l2 = 0;
  for (size_t i = 0; i < pred.size(); ++i) {  // pred → target: d1
    uint32_t j = 0;
    l1 += to_target.nearest(pred[i], &j);
    out.d_pred[i] += float(2.0 * s1) * (pred[i] - target[j]);
  }
  for (size_t j = 0; j < target.size(); ++j) {  // target → pred: d2 moves its nearest pred
    uint32_t i = 0;
    l2 += to_pred.nearest(target[j], &i);
    out.d_pred[i] += float(2.0 * s2) * (pred[i] - target[j]);
  }
  out.loss = s1 * l1 + s2 * l2;
  return out;
}

RayChamferLoss ray_chamfer_loss(const std::vector<float>& dir, const std::vector<float>& depth,
                                const std::vector<float>& gt_depth, float scale, float weight) {
  const size_t n = depth.size();
  if (dir.size() != 3 * n || gt_depth.size() != n || !(scale > 0.0f))
    throw Error("ray_chamfer_loss: " + std::to_string(dir.size()) + " direction floats, " +
                std::to_string(n) + " depths, " + std::to_string(gt_depth.size()) +
                " observed depths, scale " + std::to_string(scale));
  std::vector<Point3f> pred(n), target(n);
  for (size_t i = 0; i < n; ++i) {
    const Point3f d(dir[3 * i], dir[3 * i + 1], dir[3 * i + 2]);
    pred[i] = d * (depth[i] / scale);
    target[i] = d * (gt_depth[i] / scale);
  }
  const ChamferLoss c = chamfer_loss(pred, target, ChamferReduce::Mean);
  RayChamferLoss out;
  out.loss = double(weight) * c.loss;
  out.d_depth.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Point3f d(dir[3 * i], dir[3 * i + 1], dir[3 * i + 2]);
    out.d_depth[i] = weight * c.d_pred[i].dot(d) / scale;
  }
  return out;
}

}  // namespace sgnlf::render
