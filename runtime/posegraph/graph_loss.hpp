// The geometric pose-graph loss (method.md §3 GeoNLF; §4.2 SG-NLF's L_graph with weights α):
//   L = Σ_edges weight · (D(i→j) + D(j→i)) / #edges,
// D a direction term (robust Chamfer by default, see robust_chamfer.hpp), whose correspondences
// may be trimmed at max_distance (RobustParams). The optimiser only
// sees a PoseLoss, so a caller (or a test) can wrap the loss, and the direction term is itself a
// policy (a point-to-plane term could replace it).
// Parallelism: with threads > 1 the direction terms are shared out among threads, each written
// into its own slot and summed in edge order afterwards, so the result is bit-identical for any
// thread count.
#pragma once
#include <functional>
#include <memory>
#include <vector>

#include "posegraph/edges.hpp"
#include "posegraph/robust_chamfer.hpp"

namespace sgnlf::posegraph {

// Loss of all frames' poses T_world_lidar at temperature τ; fills grad[k] = PoseGrad of frame k
// (resized to the number of poses).
using PoseLoss =
    std::function<double(const std::vector<Pose>& T_world_lidar, double tau,
                         std::vector<PoseGrad>& grad)>;

// A direction term src→dst (robust_chamfer_direction by default).
using DirectionFn =
    std::function<DirectionTerm(const FrameCloud& src, const FrameCloud& dst,
                                const Pose& T_world_src, const Pose& T_world_dst,
                                const RobustParams& p)>;

class GraphLoss {
 public:
  // Throws sgnlf::Error for an invalid edge list (validate_edges) or threads < 1.
  GraphLoss(std::shared_ptr<const std::vector<FrameCloud>> clouds, std::vector<Edge> edges,
            double min_distance = 0.15, int threads = 1,
            DirectionFn direction = robust_chamfer_direction, double max_distance = 0.0);

  // Throws sgnlf::Error when T_world_lidar.size() differs from the number of clouds.
  double operator()(const std::vector<Pose>& T_world_lidar, double tau,
                    std::vector<PoseGrad>& grad) const;

  size_t frames() const { return clouds_->size(); }
  const std::vector<Edge>& edges() const { return edges_; }
  const std::shared_ptr<const std::vector<FrameCloud>>& clouds() const { return clouds_; }
  double min_distance() const { return min_distance_; }
  double max_distance() const { return max_distance_; }
  const DirectionFn& direction() const { return direction_; }
  // A PoseLoss sharing this object (the clouds are not copied).
  static PoseLoss as_pose_loss(std::shared_ptr<const GraphLoss> loss);

 private:
  std::shared_ptr<const std::vector<FrameCloud>> clouds_;
  std::vector<Edge> edges_;
  double min_distance_;
  int threads_;
  double max_distance_;  // RobustParams::max_distance (0: off)
  DirectionFn direction_;
};

}  // namespace sgnlf::posegraph
