// Evaluation of a trained model and of the naive baseline on a dataset's test frames
// (protocol §4 via metrics::evaluate_view): per-frame metrics and their mean.
#pragma once
#include <string>
#include <vector>

#include "core/config.hpp"
#include "pipeline/model/baked_renderer.hpp"
#include "pipeline/model/fast_renderer.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/model/scene.hpp"

namespace sgnlf::pipeline {

class RayDropStage;

struct ViewSet {
  Json per_frame = Json::array();  // [{frame: id, metrics...}, ...]
  Json mean;                       // mean over test frames
  std::vector<RangeImage> images;  // the predictions, in test-frame order (metres)
};

// Renders every test frame at T_world_lidar[frame] (metres: the ground truth for the GT-pose
// methods, the optimised pose for the pose-free ones, protocol §3) and scores it against the
// frame's observed range image. With `fast`, through the fast renderer (a diagnostic of its
// agreement: the tables use the protocol's renderer). With `refine`, every view's return
// probability is the ray-drop U-Net's (LiDAR4D, ray_drop_stage.hpp) before it is scored.
// With `baked` (and no `fast`), the views are ray-cast from a baked scene (docs/baking.md).
ViewSet evaluate_model(LidarNerfModel& model, const Dataset& d, const Scene& scene,
                       int chunk_rays, const std::vector<Pose>& T_world_lidar,
                       FastRenderer* fast = nullptr, const RayDropStage* refine = nullptr,
                       BakedRenderer* baked = nullptr);
// The naive baseline (nearest training scan moved with GT poses, metrics/naive_baseline.hpp).
ViewSet evaluate_naive(const Dataset& d);
// The same with the scans moved by `T_world_lidar` (one per frame, metres): for scans without
// reference poses, the run's own.
ViewSet evaluate_naive(const Dataset& d, const std::vector<Pose>& T_world_lidar);

}  // namespace sgnlf::pipeline
