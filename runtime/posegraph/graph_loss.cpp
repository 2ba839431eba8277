// Pose-graph loss: direction terms per edge, summed in a fixed order.
#include "posegraph/graph_loss.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <thread>

#include "core/error.hpp"

namespace sgnlf::posegraph {

GraphLoss::GraphLoss(std::shared_ptr<const std::vector<FrameCloud>> clouds,
                     std::vector<Edge> edges, double min_distance, int threads,
                     DirectionFn direction, double max_distance)
    : clouds_(std::move(clouds)), edges_(std::move(edges)), min_distance_(min_distance),
      threads_(threads), max_distance_(max_distance), direction_(std::move(direction)) {
  require(clouds_ != nullptr, "GraphLoss: no clouds");
  validate_edges(edges_, int(clouds_->size()));
  require(threads_ >= 1, "GraphLoss: threads must be >= 1, got " + std::to_string(threads_));
  require(bool(direction_), "GraphLoss: empty direction term");
  require(std::isfinite(max_distance_) && max_distance_ >= 0.0,
          "GraphLoss: max_distance must be finite and >= 0, got " + std::to_string(max_distance_));
}

double GraphLoss::operator()(const std::vector<Pose>& T, double tau,
                             std::vector<PoseGrad>& grad) const {
  const auto& clouds = *clouds_;
  require(T.size() == clouds.size(), "GraphLoss: " + std::to_string(T.size()) +
                                         " poses for " + std::to_string(clouds.size()) +
                                         " frame clouds");
  const RobustParams params{tau, min_distance_, max_distance_};
  // Slot 2e is edge e's i→j, slot 2e+1 its j→i.
  std::vector<DirectionTerm> terms(2 * edges_.size());
  std::vector<std::exception_ptr> failed(threads_);
  auto work = [&](size_t first, size_t stride) {
    try {
      for (size_t s = first; s < terms.size(); s += stride) {
        const Edge& e = edges_[s / 2];
        const int a = s % 2 == 0 ? e.i : e.j, b = s % 2 == 0 ? e.j : e.i;
        terms[s] = direction_(clouds[a], clouds[b], T[a], T[b], params);
      }
    } catch (...) {
      failed[first] = std::current_exception();  // rethrown on the calling thread
    }
  };
  const size_t n_threads = std::min(size_t(threads_), terms.size());
  if (n_threads <= 1) {
    work(0, 1);
  } else {
    std::vector<std::thread> pool;
    for (size_t t = 1; t < n_threads; ++t) pool.emplace_back(work, t, n_threads);
    work(0, n_threads);
    for (auto& th : pool) th.join();
  }
  for (const auto& f : failed)
    if (f) std::rethrow_exception(f);
  grad.assign(T.size(), PoseGrad::Zero());
  double loss = 0.0;
  const double inv_edges = 1.0 / double(edges_.size());
  for (size_t s = 0; s < terms.size(); ++s) {
    const Edge& e = edges_[s / 2];
    const int a = s % 2 == 0 ? e.i : e.j, b = s % 2 == 0 ? e.j : e.i;
    const double w = e.weight * inv_edges;
    loss += w * terms[s].loss;
    grad[a] += w * terms[s].grad_src;
    grad[b] += w * terms[s].grad_dst;
  }
  return loss;
}

PoseLoss GraphLoss::as_pose_loss(std::shared_ptr<const GraphLoss> loss) {
  require(loss != nullptr, "GraphLoss::as_pose_loss: null loss");
  return [loss](const std::vector<Pose>& T, double tau, std::vector<PoseGrad>& grad) {
    return (*loss)(T, tau, grad);
  };
}

}  // namespace sgnlf::posegraph
