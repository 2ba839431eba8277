// The training view of a dataset: scene normalisation (protocol §2) computed from the training
// frames, poses and ground-truth range images in the normalised frame, and the sensor's ray
// directions. Ranges are stored normalised (metres · scale); metrics convert back to metres.
#pragma once
#include <vector>

#include "datasets/dataset.hpp"

namespace sgnlf::pipeline {

struct Scene {
  Sensor sensor;
  SceneNormalization norm;
  std::vector<Pose> T_world_lidar;   // per dataset frame, normalised world (t ← (t − c)·s)
  std::vector<RangeImage> images;    // per dataset frame, ranges normalised
  std::vector<const RangeImage*> gt_images;  // per dataset frame, the dataset's own (metres)
  std::vector<float> directions;     // H×W×3 sensor-frame unit directions (protocol §1)
  std::vector<int> train, test;      // indices into the dataset's frames; `train` = the frames
                                     // ray batches come from
  std::vector<int> pose_only;        // frames in `train` whose steps move only their pose
                                     // (pose-free test frames, protocol §3): network lr 0
};

// Builds the scene with ground-truth poses (LiDAR-NeRF, LiDAR4D). Keeps pointers into `d`,
// which must outlive the scene.
Scene make_scene(const Dataset& d);
// The pose-free methods' scene (protocol §2–3): `T_world_lidar_init` (metres, one per dataset
// frame) gives the normalisation and the initial poses; ray batches visit every frame, the test
// frames for their poses only (pose_only).
Scene make_pose_free_scene(const Dataset& d, const std::vector<Pose>& T_world_lidar_init);

// The scene seen through another sensor (rendering only): its sensor and ray directions,
// the same normalisation, poses and splits, no range images.
Scene view_with_sensor(const Scene& scene, const Sensor& sensor);

// Pose `T_world_lidar` (metres) → normalised frame, and back.
Pose normalize_pose(const Pose& T_world_lidar, const SceneNormalization& n);
Pose denormalize_pose(const Pose& T_norm, const SceneNormalization& n);

}  // namespace sgnlf::pipeline
