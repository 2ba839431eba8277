// Voxel keys and voxel-grid downsampling (KISS-ICP §III-B). A point's voxel is
// floor(p / voxel_size) per axis; downsampling keeps the first point of each voxel in input
// order, so the result is deterministic and made of measured points (no centroids).
#pragma once
#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sgnlf::odometry {

using Point3 = Eigen::Vector3d;
using Cloud = std::vector<Point3>;
using VoxelKey = Eigen::Vector3i;

inline VoxelKey voxel_key(const Point3& p, double inv_voxel_size) {
  return VoxelKey(int(std::floor(p.x() * inv_voxel_size)), int(std::floor(p.y() * inv_voxel_size)),
                  int(std::floor(p.z() * inv_voxel_size)));
}

// Teschner et al.'s spatial hash (the one KISS-ICP uses).
struct VoxelKeyHash {
  size_t operator()(const VoxelKey& k) const {
    return size_t((uint32_t(k.x()) * 73856093u) ^ (uint32_t(k.y()) * 19349669u) ^
                  (uint32_t(k.z()) * 83492791u));
  }
};

struct VoxelKeyEqual {
  bool operator()(const VoxelKey& a, const VoxelKey& b) const {
    return a.x() == b.x() && a.y() == b.y() && a.z() == b.z();
  }
};

// First point of every occupied voxel, in input order. voxel_size > 0.
Cloud voxel_downsample(const Cloud& points, double voxel_size);

// Points whose distance to the origin lies in [min_range, max_range] and are finite.
Cloud crop_range(const Cloud& points, double min_range, double max_range);

}  // namespace sgnlf::odometry
