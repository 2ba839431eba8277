// Test fixture: point clouds sampled from smooth world surfaces (a gently curved ground and two
// curved walls, so every pose direction is constrained), seen from given poses. Smooth surfaces
// keep the nearest-neighbour loss smooth enough for finite differences.
#pragma once
#include <cmath>
#include <vector>

#include "core/rng.hpp"
#include "geometry/se3.hpp"
#include "posegraph/frame_cloud.hpp"

namespace sgnlf::test {

// n world points, a third on each surface, drawn from Rng(seed).
inline std::vector<Vec3> smooth_world_points(size_t n, uint64_t seed) {
  Rng rng(seed);
  std::vector<Vec3> pts(n);
  for (size_t k = 0; k < n; ++k) {
    const double a = rng.uniform_double() * 20.0 - 10.0, b = rng.uniform_double() * 20.0 - 10.0;
    const double h = rng.uniform_double() * 4.0;
    switch (k % 3) {
      case 0: pts[k] = Vec3(a, b, 0.3 * std::sin(0.5 * a) + 0.2 * std::cos(0.7 * b) - 2.0); break;
      case 1: pts[k] = Vec3(8.0 + 0.5 * std::sin(0.4 * b + 0.3 * h), b, h - 2.0); break;
      default: pts[k] = Vec3(a, -7.0 + 0.6 * std::cos(0.5 * a) + 0.2 * h, h - 2.0); break;
    }
  }
  return pts;
}

// The world points expressed in the LiDAR frame of T_world_lidar.
inline posegraph::FrameCloud cloud_seen_from(const std::vector<Vec3>& world,
                                             const Pose& T_world_lidar) {
  std::vector<geometry::Point3f> pts;
  const Pose T_lidar_world = T_world_lidar.inverse();
  for (const Vec3& x : world) pts.push_back((T_lidar_world * x).cast<float>());
  return posegraph::FrameCloud(std::move(pts));
}

}  // namespace sgnlf::test
