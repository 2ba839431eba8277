// scene_cloud (see scene_cloud.hpp).
#include "workflow/scene_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

#include "core/error.hpp"

namespace sgnlf::workflow {

std::vector<PointXYZI> scene_cloud(const Dataset& d, const std::vector<Pose>& T_world_lidar,
                                   double voxel_m) {
  require(T_world_lidar.size() == d.frames.size(),
          "scene_cloud: " + std::to_string(T_world_lidar.size()) + " poses for " +
              std::to_string(d.frames.size()) + " frames");
  require(voxel_m >= 0.0 && std::isfinite(voxel_m), "scene_cloud: voxel size " + std::to_string(voxel_m));
  size_t n = 0;
  for (const auto& f : d.frames) n += f.points.size();
  std::vector<PointXYZI> out;
  out.reserve(n);
  std::unordered_set<uint64_t> seen;
  // 21 bits per axis around the origin: ±1 048 576 voxels (±52 km at 5 cm).
  auto key = [&](const Vec3& w) {
    uint64_t k = 0;
    for (int a = 0; a < 3; ++a) {
      const int64_t c = int64_t(std::floor(w[a] / voxel_m)) + (int64_t(1) << 20);
      k = (k << 21) | uint64_t(std::clamp<int64_t>(c, 0, (int64_t(1) << 21) - 1));
    }
    return k;
  };
  for (size_t i = 0; i < d.frames.size(); ++i) {
    const Pose& T = T_world_lidar[i];
    for (const auto& p : d.frames[i].points) {
      const Vec3 w = T * Vec3(p.x, p.y, p.z);
      if (voxel_m > 0.0 && !seen.insert(key(w)).second) continue;
      out.push_back(PointXYZI{float(w.x()), float(w.y()), float(w.z()), p.intensity});
    }
  }
  return out;
}

}  // namespace sgnlf::workflow
