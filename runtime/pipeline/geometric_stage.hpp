// GeoNLF's geometric stage in a pose-free run (method.md §3): before each epoch, the device-free
// graph optimiser (posegraph::GeometricOptimizer, robust Chamfer over the edges (i, i+k) of the
// config's offsets) moves every pose for GeometricScheduleConfig::steps_at(epoch, progress)
// pose-only Adam steps, fresh each time. Each frame's observed scan is subsampled once
// (points_per_frame, seed 1) and its k-d tree built once in its own LiDAR frame. The optimiser
// works in metres: poses are denormalised before and normalised after. τ and the learning rates
// follow the stage's own clock (GeometricScheduleConfig::clock).
#pragma once
#include "datasets/dataset.hpp"
#include "pipeline/pose_free_step.hpp"

namespace sgnlf::pipeline {

// An empty stage when the config disables it (or the poses are not optimised).
GeometricStage make_geometric_stage(const Dataset& d, const Scene& scene, const TrainConfig& c);

// The τ scale in force for `sensor` under `g`.
double geometric_tau_scale(const GeometricScheduleConfig& g, const Sensor& sensor);

}  // namespace sgnlf::pipeline
