// The geometric optimiser run as a schedule of calls (method.md §3: coarse alignment from the
// protocol's initial poses): `steps` pose-only Adam steps in calls of `per_call`, a fresh Adam
// each call, on a clock c_k = k / calls (k = 1 … calls): τ = tau_scale · c_k sharpens the robust
// weights as the poses converge, and the learning rates decay as
// lr · lr_start · (lr_final / lr_start)^((k − 1) / calls). With hold_clock the clock stays at 1
// (τ at its final value: a refinement run on a new graph, pipeline/train/geometric_stage.cpp).
// Measured with `sgnlf posegraph` (README, "GeoNLF"): this recipe brings the noisy protocol
// start (≈ 3.25 m ATE) to ≈ 0.27 m on kitti360-low-a and nuscenes-low-a with 200 steps.
#pragma once
#include <functional>
#include <memory>
#include <vector>

#include "posegraph/geometric_optimizer.hpp"

namespace sgnlf::posegraph {

struct AnnealConfig {
  int steps = 200;
  int per_call = 10;
  double lr_final = 0.05;
  double lr_start = 1.0;
  bool hold_clock = false;
  void validate() const;  // ConfigError naming the field
};

// `on_call(k, clock, result)` after each call (e.g. to report the ATE). Returns the results.
std::vector<GeometricResult> run_annealed(
    std::shared_ptr<const GraphLoss> loss, const GeometricConfig& base, const AnnealConfig& a,
    std::vector<Pose>& T_world_lidar,
    const std::function<void(int, double, const GeometricResult&)>& on_call = {});
// The same schedule over any loss of `frames` poses (e.g. a graph that on_call rebuilds between
// calls: staged_graph_run.hpp).
std::vector<GeometricResult> run_annealed(
    PoseLoss loss, size_t frames, const GeometricConfig& base, const AnnealConfig& a,
    std::vector<Pose>& T_world_lidar,
    const std::function<void(int, double, const GeometricResult&)>& on_call = {});

}  // namespace sgnlf::posegraph
