// VoxelHashMap (see voxel_map.hpp).
#include "odometry/voxel_map.hpp"

#include <limits>

#include "core/error.hpp"

namespace sgnlf::odometry {

VoxelHashMap::VoxelHashMap(double voxel_size, int max_points_per_voxel, double max_distance)
    : voxel_size_(voxel_size),
      inv_voxel_size_(1.0 / voxel_size),
      max_distance_(max_distance),
      max_points_(max_points_per_voxel) {
  if (!(voxel_size > 0) || max_points_per_voxel < 1 || !(max_distance > 0))
    throw Error("VoxelHashMap: voxel size, points per voxel and max distance must be > 0");
}

size_t VoxelHashMap::num_points() const {
  size_t n = 0;
  for (const auto& kv : map_) n += kv.second.size();
  return n;
}

void VoxelHashMap::add_points(const Cloud& points_world) {
  for (const Point3& p : points_world) {
    auto& voxel = map_[voxel_key(p, inv_voxel_size_)];
    if (int(voxel.size()) < max_points_) {
      if (voxel.empty()) voxel.reserve(size_t(max_points_));
      voxel.push_back(p);
    }
  }
}

void VoxelHashMap::remove_far(const Point3& origin_world) {
  const double max2 = max_distance_ * max_distance_;
  for (auto it = map_.begin(); it != map_.end();) {
    if ((it->second.front() - origin_world).squaredNorm() > max2)
      it = map_.erase(it);
    else
      ++it;
  }
}

namespace {

// The 27 neighbour offsets, the query's own voxel first, then the 6 face, 12 edge and 8 corner
// neighbours, so that the nearer cells usually tighten the bound before the farther ones.
struct Offsets {
  int d[27][3];
  Offsets() {
    int n = 0;
    for (int nonzero = 0; nonzero <= 3; ++nonzero)
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz)
            if ((dx != 0) + (dy != 0) + (dz != 0) == nonzero) {
              d[n][0] = dx;
              d[n][1] = dy;
              d[n][2] = dz;
              ++n;
            }
  }
};
const Offsets kOffsets;

}  // namespace

bool VoxelHashMap::nearest(const Point3& q, Point3& nearest_point, double& squared_distance) const {
  const VoxelKey c = voxel_key(q, inv_voxel_size_);
  // Squared distance from q to the lower and upper faces of its voxel per axis: a neighbour
  // cell's lower bound is the sum over its non-zero offsets, and a cell whose bound is not
  // below the best distance so far cannot hold a nearer point (skipped; the result is the
  // same as visiting all 27 cells).
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    const double t = q[a] - double(c[a]) * voxel_size_;
    lo[a] = t * t;
    hi[a] = (voxel_size_ - t) * (voxel_size_ - t);
  }
  double best = std::numeric_limits<double>::infinity();
  const Point3* best_p = nullptr;
  for (const auto& o : kOffsets.d) {
    double bound = 0.0;
    for (int a = 0; a < 3; ++a) bound += o[a] < 0 ? lo[a] : (o[a] > 0 ? hi[a] : 0.0);
    if (bound >= best) continue;
    const auto it = map_.find(VoxelKey(c.x() + o[0], c.y() + o[1], c.z() + o[2]));
    if (it == map_.end()) continue;
    for (const Point3& p : it->second) {
      const double d2 = (p - q).squaredNorm();
      if (d2 < best) {
        best = d2;
        best_p = &p;
      }
    }
  }
  if (!best_p) return false;
  nearest_point = *best_p;
  squared_distance = best;
  return true;
}

Cloud VoxelHashMap::points() const {
  Cloud out;
  out.reserve(num_points());
  for (const auto& kv : map_) out.insert(out.end(), kv.second.begin(), kv.second.end());
  return out;
}

}  // namespace sgnlf::odometry
