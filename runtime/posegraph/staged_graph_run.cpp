// run_staged_graph (see staged_graph_run.hpp).
#include "posegraph/staged_graph_run.hpp"

#include <cmath>

#include "core/config.hpp"
#include "core/error.hpp"

namespace sgnlf::posegraph {

void StagedGraphConfig::validate() const {
  anneal.validate();
  check_range("staged graph run", "confidence_start", confidence_start, 0.0, 1.0);
}

StagedGraphResult run_staged_graph(
    std::shared_ptr<const std::vector<FrameCloud>> clouds, const GeometricConfig& base,
    const StagedGraphConfig& s, const ConfidenceGraphConfig& gc, const FeatureProvider& features,
    std::vector<Pose>& T, const std::function<void(int, double, const GeometricResult&)>& on_call,
    const std::function<void(const GraphEvaluation&)>& on_graph) {
  require(clouds != nullptr, "run_staged_graph: no clouds");
  s.validate();
  gc.validate();
  base.validate();
  const size_t n = clouds->size();
  const int calls = (s.anneal.steps + s.anneal.per_call - 1) / s.anneal.per_call;
  const int k0 = int(std::lround(s.confidence_start * calls));

  // The loss the calls see: a GraphLoss swapped between calls.
  auto current = std::make_shared<std::shared_ptr<const GraphLoss>>(
      std::make_shared<const GraphLoss>(clouds, sequential_edges(int(n), gc.sequential_offsets),
                                        base.min_distance, base.threads, base.direction()));
  const PoseLoss loss = [current](const std::vector<Pose>& poses, double tau,
                                  std::vector<PoseGrad>& grad) {
    return (**current)(poses, tau, grad);
  };
  StagedGraphResult out;
  auto rebuild = [&](int after_call) {
    GraphEvaluation e{after_call, build_confidence_graph(*clouds, T, features, gc)};
    *current = std::make_shared<const GraphLoss>(clouds, e.graph.edges, base.min_distance,
                                                 base.threads, base.direction(),
                                                 gc.edge_max_distance_m);
    if (on_graph) on_graph(e);
    out.graphs.push_back(std::move(e));
  };
  const bool use_graph = s.confidence;
  if (use_graph && k0 == 0) rebuild(0);
  out.calls = run_annealed(
      loss, n, base, s.anneal, T, [&](int k, double clock, const GeometricResult& r) {
        if (on_call) on_call(k, clock, r);
        if (use_graph && k < calls && k >= k0 && (k - k0) % gc.reevaluate_every == 0)
          rebuild(k);
      });
  return out;
}

}  // namespace sgnlf::posegraph
