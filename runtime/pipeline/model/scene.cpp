// Scene: normalisation and per-frame normalised poses and ranges (protocol §2).
#include "pipeline/model/scene.hpp"

#include <cmath>

#include "core/error.hpp"
#include "datasets/protocol.hpp"

namespace sgnlf::pipeline {

Pose normalize_pose(const Pose& T, const SceneNormalization& n) {
  Pose out = T;
  out.translation() = (T.translation() - n.center) * n.scale;
  return out;
}

Pose denormalize_pose(const Pose& T, const SceneNormalization& n) {
  Pose out = T;
  out.translation() = T.translation() / n.scale + n.center;
  return out;
}

namespace {

Scene scene_with_poses(const Dataset& d, const std::vector<Pose>& poses) {
  if (d.split.train.empty()) throw Error("dataset " + d.name + ": no training frames");
  if (poses.size() != d.frames.size())
    throw Error("dataset " + d.name + ": " + std::to_string(poses.size()) + " poses for " +
                std::to_string(d.frames.size()) + " frames");
  Scene s;
  s.sensor = d.sensor;
  s.train = d.split.train;
  s.test = d.split.test;
  s.norm = compute_normalization(d, poses, d.split.train);
  if (!(s.norm.scale > 0.0) || !std::isfinite(s.norm.scale))
    throw NumericError("dataset " + d.name + ": degenerate scene normalisation (scale " +
                       std::to_string(s.norm.scale) + ")");
  s.directions = ray_directions(d.sensor);
  for (size_t i = 0; i < d.frames.size(); ++i) {
    s.T_world_lidar.push_back(normalize_pose(poses[i], s.norm));
    s.gt_images.push_back(&d.frames[i].image);
    RangeImage img = d.frames[i].image;
    if (img.height != d.sensor.height || img.width != d.sensor.width)
      throw Error("dataset " + d.name + ": frame " + std::to_string(d.frames[i].id) +
                  " range image is " + std::to_string(img.height) + "x" +
                  std::to_string(img.width) + ", sensor is " + std::to_string(d.sensor.height) +
                  "x" + std::to_string(d.sensor.width));
    for (auto& r : img.range) r = float(r * s.norm.scale);
    s.images.push_back(std::move(img));
  }
  return s;
}

}  // namespace

Scene make_scene(const Dataset& d) { return scene_with_poses(d, gt_poses(d)); }

Scene make_pose_free_scene(const Dataset& d, const std::vector<Pose>& T_world_lidar_init) {
  for (size_t i = 0; i < T_world_lidar_init.size(); ++i)
    if (!T_world_lidar_init[i].matrix().allFinite())
      throw NumericError("dataset " + d.name + ": initial pose of frame " +
                         std::to_string(i < d.frames.size() ? d.frames[i].id : int(i)) +
                         " is not finite");
  Scene s = scene_with_poses(d, T_world_lidar_init);
  s.train.clear();
  for (int i = 0; i < int(d.frames.size()); ++i) s.train.push_back(i);
  s.pose_only = d.split.test;
  return s;
}

Scene view_with_sensor(const Scene& scene, const Sensor& sensor) {
  sensor.validate();
  Scene v;
  v.sensor = sensor;
  v.norm = scene.norm;
  v.T_world_lidar = scene.T_world_lidar;
  v.directions = ray_directions(sensor);
  v.train = scene.train;
  v.test = scene.test;
  v.pose_only = scene.pose_only;
  return v;
}

}  // namespace sgnlf::pipeline
