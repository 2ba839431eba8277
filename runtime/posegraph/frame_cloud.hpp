// One frame's point cloud for the geometric pose optimiser (GeoNLF, method.md §3): a fixed
// subsample of the observed scan in the frame's own LiDAR coordinates and a k-d tree built ONCE
// in that frame. A pose change moves the queries (T_dst⁻¹·T_src·p), never the tree.
#pragma once
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "geometry/kdtree.hpp"
#include "geometry/range_image.hpp"
#include "posegraph/frame_normals.hpp"

namespace sgnlf::posegraph {

struct FrameCloud {
  std::vector<geometry::Point3f> points;  // LiDAR frame, metres
  geometry::KdTree tree;                  // over `points`, same frame
  // Unit normal (or zero, frame_normals.hpp) of each point, same frame; empty unless a
  // point-to-plane term needs them (make_frame_clouds with NormalOptions).
  std::vector<geometry::Point3f> normals;

  // Throws sgnlf::Error when `points` is empty or holds a non-finite point.
  explicit FrameCloud(std::vector<geometry::Point3f> points_lidar);
  size_t size() const { return points.size(); }
};

// Indices of min(max_points, n) of n points, without replacement, in increasing order (scan
// order is kept). Deterministic: a partial Fisher-Yates shuffle driven by the project's Philox
// Rng(seed, stream); every index is equally likely to be picked. max_points = 0 keeps all.
std::vector<uint32_t> subsample_indices(size_t n, size_t max_points, uint64_t seed,
                                        uint32_t stream);

// Subsample of a scan (stream = frame index, so frames draw independent subsets).
std::vector<geometry::Point3f> subsample_points(const std::vector<Eigen::Vector3f>& scan,
                                                size_t max_points, uint64_t seed, uint32_t stream);
std::vector<geometry::Point3f> subsample_points(const std::vector<PointXYZI>& scan,
                                                size_t max_points, uint64_t seed, uint32_t stream);

// One FrameCloud per scan: subsample_points(scans[k], max_points, seed, stream = k); with
// `normals`, each point's normal estimated in its whole scan.
std::vector<FrameCloud> make_frame_clouds(const std::vector<std::vector<PointXYZI>>& scans,
                                          size_t max_points, uint64_t seed,
                                          const NormalOptions* normals = nullptr);

}  // namespace sgnlf::posegraph
