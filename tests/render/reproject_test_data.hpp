// Inputs of the cross-frame reprojection tests: two consecutive frames of the simulator's
// low-frequency sequences (2 Hz, metres, ground-truth poses), simulated once per binary, and a
// helper that runs the device forward on host data.
#pragma once
#include <map>
#include <string>

#include "datasets/simulate.hpp"
#include "render/cross_frame_reprojection.hpp"
#include "support/test_device.hpp"

namespace sgnlf::test {

// Frames 0 and 1 of "kitti360-low-a" or "nuscenes-low-a" at the sensor's full size, or
// narrowed to `width` columns (−1 = full).
inline const Dataset& reproj_pair(const std::string& sequence, int width = -1) {
  static std::map<std::pair<std::string, int>, Dataset> cache;
  auto it = cache.find({sequence, width});
  if (it == cache.end()) {
    SimOptions o;
    o.sequence = sequence;
    o.frames = 2;
    o.width = width;
    o.threads = 1;
    it = cache.emplace(std::make_pair(sequence, width), simulate_dataset(o)).first;
  }
  return it->second;
}

struct DeviceReprojection {
  render::ReprojectionContext ctx;
  render::ReprojectionImages images;
};

inline DeviceReprojection device_reproject(render::CrossFrameReprojection& rp,
                                           const std::vector<float>& depth_i,
                                           const Pose& T_world_lidar_i,
                                           const Pose& T_world_lidar_j) {
  auto& rt = runtime();
  auto depth = cl::Buffer::from(rt, depth_i);
  auto out = rp.make_output();
  DeviceReprojection r;
  r.ctx = rp.forward(depth, T_world_lidar_i, T_world_lidar_j, out);
  r.images = rp.read(out);
  return r;
}

inline Pose make_pose(const Vec3& omega, const Vec3& t) {
  Pose T = Pose::Identity();
  T.linear() = exp_so3(omega);
  T.translation() = t;
  return T;
}

}  // namespace sgnlf::test
