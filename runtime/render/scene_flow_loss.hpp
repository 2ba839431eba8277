// LiDAR4D's scene-flow supervision (method.md §2; LiDAR4D model/runner.py): the ground-removed
// points P_k of frame k, moved by the predicted flow, should cover the neighbouring frames'
// ground-removed points:
//   L = Σ_{s∈{1,2}} [ C(P_k + s·flow_fwd, P_{k+s}) + C(P_k + s·flow_bwd, P_{k−s}) ],
// C the summed Chamfer term 0.5·(Σ d1 + Σ d2) (render/chamfer_loss.hpp), a missing frame
// (beyond the sequence) contributing nothing; LiDAR4D's "two-step consistency" takes s = 1, 2
// (steps = 2 here by default; steps = 1 is the one-frame loss). On the ground points G_k
// (the removed ones) the flow is pulled to zero: weight · Σ |flow| (weight 0.001). The flow
// is given per point (N × 6, forward then backward), as SceneFlow computes it; the gradient
// dL/dflow has the same layout.
#pragma once
#include <vector>

#include "render/chamfer_loss.hpp"

namespace sgnlf::render {

// The frames around k; a null or empty set is a frame that does not exist.
struct FlowNeighbours {
  const std::vector<Point3f>* next[2] = {nullptr, nullptr};  // k + 1, k + 2
  const std::vector<Point3f>* prev[2] = {nullptr, nullptr};  // k − 1, k − 2
};

struct SceneFlowLoss {
  double loss = 0.0;
  std::vector<float> d_flow;  // N × 6
};

SceneFlowLoss scene_flow_loss(const std::vector<Point3f>& points, const std::vector<float>& flow,
                              const FlowNeighbours& neighbours, int steps = 2);

// weight · Σ |flow| over ground points' flows (N × 6), gradient weight · sign(flow).
SceneFlowLoss ground_flow_penalty(const std::vector<float>& flow, float weight = 0.001f);

}  // namespace sgnlf::render
