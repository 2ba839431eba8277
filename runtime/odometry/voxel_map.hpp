// The local map (KISS-ICP §III-B): a hash map from voxel keys to at most `max_points_per_voxel`
// world-frame points, first come first kept, voxels farther than `max_distance` from the
// sensor dropped after each update. Nearest-neighbour search looks at the query's voxel and its
// 26 neighbours, so it is exact whenever the true nearest point lies within one voxel size of
// the query (tests compare it with a brute-force search); farther points may be missed.
// Storage: an open-addressing table (linear probing, load ≤ 1/4: most of a query's probes are
// for empty cells, whose probe sequence ends at the first empty slot) from keys to blocks of
// max_points_per_voxel points, contiguous per voxel, so that one probe and one cache-friendly
// run serve each cell of a query; removal rebuilds the table (once per frame).
// Points are stored in float: the search is bound by memory traffic (each query reads ~7 slots
// and 15–30 points), and 12-byte points halve the blocks' cache lines (scene-0916: ~10 % less
// CPU per scan). Rounding moves a point by ≤ 2^-24 of its coordinates (< 0.1 mm within 1 km of
// the first pose); distances, the returned point and the ICP's sums stay in double, so the
// search is exact with respect to the stored points.
#pragma once
#include <cstdint>
#include <vector>

#include "odometry/voxel_grid.hpp"

namespace sgnlf::odometry {

class VoxelHashMap {
 public:
  VoxelHashMap(double voxel_size, int max_points_per_voxel, double max_distance);

  bool empty() const { return voxels_ == 0; }
  size_t num_voxels() const { return voxels_; }
  size_t num_points() const { return points_total_; }
  double voxel_size() const { return voxel_size_; }

  // Adds world-frame points, voxel by voxel in input order.
  void add_points(const Cloud& points_world);
  // Drops voxels whose first point is farther than max_distance from `origin_world`.
  void remove_far(const Point3& origin_world);
  // add_points then remove_far around the sensor position.
  void update(const Cloud& points_world, const Point3& origin_world) {
    add_points(points_world);
    remove_far(origin_world);
  }
  void clear();

  // Nearest map point among the 27 voxels around `q`; false when they are all empty. The point
  // and its squared distance (computed in double) are those of the stored, float-rounded point.
  bool nearest(const Point3& q, Point3& nearest_point, double& squared_distance) const;
  // Every stored point, in an unspecified but deterministic order (tests, pictures).
  Cloud points() const;

 private:
  struct Slot {
    VoxelKey key;
    int32_t block = -1;  // −1: empty
  };
  // The block of `key`, or −1.
  int32_t find(const VoxelKey& key) const;
  // The block of `key`, created empty when absent.
  int32_t find_or_insert(const VoxelKey& key);
  void rehash(size_t capacity);

  double voxel_size_, inv_voxel_size_, max_distance_;
  int max_points_;
  std::vector<Slot> slots_;       // capacity a power of two
  using MapPoint = Eigen::Vector3f;  // see the top comment
  std::vector<MapPoint> points_;     // block b holds points_[b·max_points_ …]
  std::vector<int32_t> counts_;   // points in each block
  std::vector<VoxelKey> keys_;    // key of each block
  size_t voxels_ = 0, points_total_ = 0;
};

}  // namespace sgnlf::odometry
