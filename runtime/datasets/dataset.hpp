// The in-memory dataset every method trains and evaluates on: frames with their scans and
// ground-truth LiDAR poses, the sensor, and the protocol split. Loaders (KITTI-360, KITTI
// odometry, nuScenes, the synthetic layout) all produce this. Contract shared by datasets,
// metrics and pipeline: extend it, do not change the meaning of existing fields.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/range_image.hpp"
#include "geometry/se3.hpp"
#include "geometry/sensor.hpp"

namespace sgnlf {

// A moving actor at one frame's time (synthetic data with actors, datasets/README.md): its
// pose (x forward along its motion, z up, origin at the box centre) and half extents (a
// pedestrian is an upright cylinder of radius half.x() inside that box).
struct ActorBox {
  int id = 0;              // the label its returns carry (1, 2, ...)
  std::string kind;        // "vehicle" or "pedestrian"
  Pose T_world_actor = Pose::Identity();
  Vec3 half_extents = Vec3::Zero();
};

struct Frame {
  int id = 0;                 // frame number in the source sequence
  double timestamp_s = 0.0;   // seconds since the first frame of the sequence
  Pose T_world_lidar = Pose::Identity();  // ground truth (metres)
  std::vector<PointXYZI> points;          // scan in the LiDAR frame, intensity in [0, 1]
  RangeImage image;                       // projection of `points` (protocol §1)
  // Synthetic sequences with moving actors only (else empty): per point of `points`, 0 for the
  // static world, k for a return from actor k; and every actor's box at the frame's time.
  std::vector<uint16_t> labels;
  std::vector<ActorBox> actors;
};

struct Split {
  std::vector<int> train;  // indices into Dataset::frames
  std::vector<int> test;   // test views (protocol §3)
};

// Scene normalisation (protocol §2): p_norm = (p_world − center) · scale.
struct SceneNormalization {
  Vec3 center = Vec3::Zero();
  double scale = 1.0;
};

struct Dataset {
  std::string name;      // sequence name
  std::string source;    // "synthetic", "kitti360", "kitti-odometry", "nuscenes", "scans"
  std::string path;      // where it was loaded from
  std::string frequency; // "standard" or "low"
  Sensor sensor;
  std::vector<Frame> frames;
  Split split;
  // False for scans without poses (a plain folder of scans): the frames' T_world_lidar are
  // then the identity, not a reference, and nothing may score poses against them.
  bool has_reference_poses = true;
  // The reference poses are planar: nuScenes' ego poses carry z = 0, so the LiDAR's reference
  // height moves only with roll and pitch and the scans' climb is not in it. Pose accuracy is
  // then judged horizontally (metrics::PoseReference::horizontal). Set by the nuScenes loader,
  // and by the synthetic-layout loader for a window copied from nuScenes (sgnlf_dataset.json:
  // "planar_reference", or "real_source": "nuscenes" in folders written before the key).
  bool planar_reference = false;
};

}  // namespace sgnlf
