// VoxelHashMap (see voxel_map.hpp).
#include "odometry/voxel_map.hpp"

#include <algorithm>
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
  slots_.resize(1024);
}

void VoxelHashMap::clear() {
  slots_.assign(1024, Slot{});
  points_.clear();
  counts_.clear();
  keys_.clear();
  voxels_ = points_total_ = 0;
}

int32_t VoxelHashMap::find(const VoxelKey& key) const {
  const size_t mask = slots_.size() - 1;
  for (size_t i = VoxelKeyHash{}(key) & mask;; i = (i + 1) & mask) {
    const Slot& s = slots_[i];
    if (s.block < 0) return -1;
    if (VoxelKeyEqual{}(s.key, key)) return s.block;
  }
}

int32_t VoxelHashMap::find_or_insert(const VoxelKey& key) {
  if (4 * (voxels_ + 1) > slots_.size()) rehash(2 * slots_.size());
  const size_t mask = slots_.size() - 1;
  size_t i = VoxelKeyHash{}(key) & mask;
  for (;; i = (i + 1) & mask) {
    const Slot& s = slots_[i];
    if (s.block < 0) break;
    if (VoxelKeyEqual{}(s.key, key)) return s.block;
  }
  const int32_t b = int32_t(voxels_++);
  slots_[i] = Slot{key, b};
  keys_.push_back(key);
  counts_.push_back(0);
  points_.resize(points_.size() + size_t(max_points_));
  return b;
}

void VoxelHashMap::rehash(size_t capacity) {
  slots_.assign(capacity, Slot{});
  const size_t mask = capacity - 1;
  for (size_t b = 0; b < voxels_; ++b) {
    size_t i = VoxelKeyHash{}(keys_[b]) & mask;
    while (slots_[i].block >= 0) i = (i + 1) & mask;
    slots_[i] = Slot{keys_[b], int32_t(b)};
  }
}

void VoxelHashMap::add_points(const Cloud& points_world) {
  for (const Point3& p : points_world) {
    const int32_t b = find_or_insert(voxel_key(p, inv_voxel_size_));
    int32_t& n = counts_[size_t(b)];
    if (n < max_points_) {
      points_[size_t(b) * size_t(max_points_) + size_t(n)] = p.cast<float>();
      ++n;
      ++points_total_;
    }
  }
}

void VoxelHashMap::remove_far(const Point3& origin_world) {
  // Compacts the kept blocks in their order (deterministic), then rebuilds the table.
  const double max2 = max_distance_ * max_distance_;
  const size_t m = size_t(max_points_);
  size_t kept = 0;
  points_total_ = 0;
  for (size_t b = 0; b < voxels_; ++b) {
    if ((points_[b * m].cast<double>() - origin_world).squaredNorm() > max2) continue;
    if (kept != b) {
      std::copy(points_.begin() + long(b * m), points_.begin() + long(b * m + m),
                points_.begin() + long(kept * m));
      counts_[kept] = counts_[b];
      keys_[kept] = keys_[b];
    }
    points_total_ += size_t(counts_[kept]);
    ++kept;
  }
  if (kept == voxels_) return;
  voxels_ = kept;
  points_.resize(kept * m);
  counts_.resize(kept);
  keys_.resize(kept);
  size_t cap = 1024;
  while (cap < 4 * kept + 4) cap *= 2;
  rehash(cap);
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
  // face[a][o + 1]: that squared distance for offset o ∈ {−1, 0, 1} along axis a (a table, not
  // branches: the offsets' signs are unpredictable).
  double face[3][3];
  for (int a = 0; a < 3; ++a) {
    const double t = q[a] - double(c[a]) * voxel_size_;
    face[a][0] = t * t;
    face[a][1] = 0.0;
    face[a][2] = (voxel_size_ - t) * (voxel_size_ - t);
  }
  double best = std::numeric_limits<double>::infinity();
  const MapPoint* best_p = nullptr;
  for (const auto& o : kOffsets.d) {
    const double bound = face[0][o[0] + 1] + face[1][o[1] + 1] + face[2][o[2] + 1];
    if (bound >= best) continue;
    const int32_t b = find(VoxelKey(c.x() + o[0], c.y() + o[1], c.z() + o[2]));
    if (b < 0) continue;
    const MapPoint* p = &points_[size_t(b) * size_t(max_points_)];
    const MapPoint* end = p + counts_[size_t(b)];
    for (; p != end; ++p) {
      const double dx = double(p->x()) - q.x(), dy = double(p->y()) - q.y(),
                   dz = double(p->z()) - q.z();
      const double d2 = dx * dx + dy * dy + dz * dz;
      if (d2 < best) {
        best = d2;
        best_p = p;
      }
    }
  }
  if (!best_p) return false;
  nearest_point = best_p->cast<double>();
  squared_distance = best;
  return true;
}

Cloud VoxelHashMap::points() const {
  Cloud out;
  out.reserve(points_total_);
  for (size_t b = 0; b < voxels_; ++b) {
    const MapPoint* p = &points_[b * size_t(max_points_)];
    for (int k = 0; k < counts_[b]; ++k) out.push_back(p[k].cast<double>());
  }
  return out;
}

}  // namespace sgnlf::odometry
