// LiDAR4D's scene-flow losses (render/scene_flow_loss.hpp).
#include "render/scene_flow_loss.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace sgnlf::render {

SceneFlowLoss scene_flow_loss(const std::vector<Point3f>& points, const std::vector<float>& flow,
                              const FlowNeighbours& neighbours, int steps) {
  const size_t n = points.size();
  if (flow.size() != 6 * n)
    throw Error("scene_flow_loss: " + std::to_string(flow.size()) + " flow floats for " +
                std::to_string(n) + " points (need 6 per point)");
  if (steps < 1 || steps > 2)
    throw Error("scene_flow_loss: steps = " + std::to_string(steps) + " must be 1 or 2");
  SceneFlowLoss out;
  out.d_flow.assign(6 * n, 0.0f);
  for (int side = 0; side < 2; ++side)  // 0: forward flow to k + s, 1: backward to k − s
    for (int s = 1; s <= steps; ++s) {
      const std::vector<Point3f>* target =
          side == 0 ? neighbours.next[s - 1] : neighbours.prev[s - 1];
      if (!target || target->empty()) continue;
      std::vector<Point3f> moved(n);
      for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k)
          moved[i][k] = points[i][k] + float(s) * flow[6 * i + size_t(3 * side + k)];
      const ChamferLoss c = chamfer_loss(moved, *target, ChamferReduce::Sum);
      out.loss += c.loss;
      for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k)
          out.d_flow[6 * i + size_t(3 * side + k)] += float(s) * c.d_pred[i][k];
    }
  return out;
}

SceneFlowLoss ground_flow_penalty(const std::vector<float>& flow, float weight) {
  SceneFlowLoss out;
  out.d_flow.resize(flow.size());
  double sum = 0;
  for (size_t i = 0; i < flow.size(); ++i) {
    sum += std::abs(double(flow[i]));
    out.d_flow[i] = flow[i] > 0.0f ? weight : flow[i] < 0.0f ? -weight : 0.0f;
  }
  out.loss = double(weight) * sum;
  return out;
}

}  // namespace sgnlf::render
