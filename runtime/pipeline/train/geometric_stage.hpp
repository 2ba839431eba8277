// GeoNLF's geometric stage in a pose-free run (method.md §3): before each epoch, the device-free
// graph optimiser (posegraph::GeometricOptimizer, robust Chamfer over the edges (i, i+k) of the
// optimizer's offsets) moves every pose for GeometricScheduleConfig::steps_at(epoch, progress)
// pose-only Adam steps, fresh each time. Each frame's observed scan is subsampled once
// (points_per_frame, its seed) and its k-d tree built once in its own LiDAR frame. The optimiser
// works in metres: poses are denormalised before and normalised after. τ and the learning rates
// follow the stage's own clock (GeometricScheduleConfig::clock).
#pragma once
#include "datasets/dataset.hpp"
#include "pipeline/train/pose_free_step.hpp"
#include "posegraph/point_features.hpp"

namespace sgnlf::pipeline {

// An empty stage when the config has no "geometric" section.
// SG-NLF (TrainConfig::confidence_graph()): from pose_graph.start_epoch on, every
// graph.reevaluate_every epochs, the refinement's graph is rebuilt as the confidence-aware pose
// graph (posegraph::build_confidence_graph) from `features` (the field's f_hyb) under the current
// poses, written to <run_dir>/pose_graph/epoch_<e>.json and .svg (and latest.json), and carried
// in checkpoints, so a resumed run continues on the same graph. Epoch 0's coarse alignment
// stays sequential.
GeometricStage make_geometric_stage(const Dataset& d, const Scene& scene, const TrainConfig& c,
                                    posegraph::FeatureProvider features = {},
                                    std::string run_dir = "");

// The field's encodings as the pose graph's per-point features: world points (metres) are
// normalised, clamped to the scene box and encoded by `model` (blocking; between steps only).
posegraph::FeatureProvider field_features(LidarNerfModel& model, const SceneNormalization& norm);

// The τ scale in force for `sensor`: `tau_scale`, or when it is negative GeoNLF's published
// 0.5 (nuScenes) / 0.3 (KITTI) (sgnlf posegraph's --tau-scale).
double geometric_tau_scale(double tau_scale, const Sensor& sensor);

}  // namespace sgnlf::pipeline
