// Scene: normalisation and per-frame normalised poses and ranges (protocol §2).
#include "pipeline/scene.hpp"

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

Scene make_scene(const Dataset& d) {
  if (d.split.train.empty()) throw Error("dataset " + d.name + ": no training frames");
  Scene s;
  s.sensor = d.sensor;
  s.train = d.split.train;
  s.test = d.split.test;
  const auto poses = gt_poses(d);
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

}  // namespace sgnlf::pipeline
