// Voxel-grid downsampling and range cropping (see voxel_grid.hpp).
#include "odometry/voxel_grid.hpp"

#include <unordered_set>

#include "core/error.hpp"

namespace sgnlf::odometry {

Cloud voxel_downsample(const Cloud& points, double voxel_size) {
  if (!(voxel_size > 0)) throw Error("voxel_downsample: voxel size must be > 0");
  const double inv = 1.0 / voxel_size;
  std::unordered_set<VoxelKey, VoxelKeyHash, VoxelKeyEqual> seen;
  seen.reserve(points.size());
  Cloud out;
  out.reserve(points.size() / 4);
  for (const Point3& p : points)
    if (seen.insert(voxel_key(p, inv)).second) out.push_back(p);
  return out;
}

Cloud crop_range(const Cloud& points, double min_range, double max_range) {
  Cloud out;
  out.reserve(points.size());
  const double lo2 = min_range * min_range, hi2 = max_range * max_range;
  for (const Point3& p : points) {
    if (!p.allFinite()) continue;
    const double r2 = p.squaredNorm();
    if (r2 >= lo2 && r2 <= hi2) out.push_back(p);
  }
  return out;
}

}  // namespace sgnlf::odometry
