// Voxel downsampling for the coarse level of coarse-to-fine matching (method.md §4.2): the
// points are binned into cubes of side `voxel_m` aligned with the axes of their frame (the world
// under the current poses); each occupied voxel is represented by its member closest to the
// members' centroid (ties: lowest index), so the coarse level reuses the points' features.
// Voxels are numbered in the order their first member appears: deterministic.
#pragma once
#include <cstdint>
#include <vector>

#include "geometry/kdtree.hpp"

namespace sgnlf::posegraph {

struct VoxelGrid {
  std::vector<uint32_t> representative;  // per voxel: index of its representative point
  std::vector<uint32_t> voxel_of;        // per point: its voxel
  size_t voxels() const { return representative.size(); }
};

// Throws sgnlf::Error for voxel_m ≤ 0 or not finite, a non-finite point, or a point so far out
// that its voxel coordinate leaves ±2^20 (voxel keys are packed into 64 bits).
VoxelGrid voxel_downsample(const std::vector<geometry::Point3f>& x, double voxel_m);

}  // namespace sgnlf::posegraph
