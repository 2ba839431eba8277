// Rendering full range images from a trained model at any pose (in chunks of rays), in metres:
// range = rendered depth / scale, intensity, ray_drop = predicted return probability (the
// metrics apply the > 0.5 mask, protocol §1/§4).
#pragma once
#include "pipeline/model/model.hpp"
#include "pipeline/model/scene.hpp"

namespace sgnlf::pipeline {

// `T_world_lidar` in metres (dataset frame); chunk = rays per device call (≤ model capacity).
RangeImage render_view(LidarNerfModel& model, const Scene& scene, const Pose& T_world_lidar,
                       int chunk_rays);

// The prediction as the metrics see it: range and intensity multiplied by (prob > 0.5).
RangeImage masked_prediction(const RangeImage& pred);

}  // namespace sgnlf::pipeline
