// The coarse-to-fine schedule of SG-NLF's pose graph (method.md §4.2, "Caution"): non-adjacent
// edges are only safe once the sequential graph has converged. One annealed run of the
// geometric optimiser (annealed_run.hpp: τ and learning rates on one clock over all calls):
//   calls 1 … k0             on the sequential graph (sequential_offsets, weight 1: GeoNLF's);
//   after call k0, and again every reevaluate_every calls, the confidence graph is rebuilt
//   under the current poses (build_confidence_graph) and the next calls use its weighted edges.
// k0 = round(confidence_start · calls); confidence_start = 0 builds the first graph before the
// first call (from the initial poses: the ablation without the schedule). confidence = false
// keeps the sequential graph throughout (the sequential-only baseline).
#pragma once
#include <functional>
#include <memory>
#include <vector>

#include "posegraph/annealed_run.hpp"
#include "posegraph/confidence_graph.hpp"

namespace sgnlf::posegraph {

struct StagedGraphConfig {
  AnnealConfig anneal;            // steps, per_call, lr_final of the whole run
  double confidence_start = 0.5;  // fraction of the calls before the first confidence graph
  bool confidence = true;
  void validate() const;          // ConfigError naming the field
};

struct GraphEvaluation {
  int after_call = 0;  // built from the poses after this call (0: the initial poses)
  ConfidenceGraph graph;
};

struct StagedGraphResult {
  std::vector<GeometricResult> calls;
  std::vector<GraphEvaluation> graphs;  // every (re-)evaluation, in order
};

// `base` gives the optimiser's learning rates, τ scale, min_distance and threads (its
// edge_offsets are not used: the sequential graph is graph_cfg.sequential_offsets). on_call as
// in run_annealed; on_graph after each graph is built (before the calls that use it).
StagedGraphResult run_staged_graph(
    std::shared_ptr<const std::vector<FrameCloud>> clouds, const GeometricConfig& base,
    const StagedGraphConfig& schedule, const ConfidenceGraphConfig& graph_cfg,
    const FeatureProvider& features, std::vector<Pose>& T_world_lidar,
    const std::function<void(int, double, const GeometricResult&)>& on_call = {},
    const std::function<void(const GraphEvaluation&)>& on_graph = {});

}  // namespace sgnlf::posegraph
