// Frame clouds: deterministic subsampling and the per-frame k-d tree.
#include "posegraph/frame_cloud.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <string>

#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf::posegraph {

FrameCloud::FrameCloud(std::vector<geometry::Point3f> points_lidar)
    : points(std::move(points_lidar)), tree(points) {
  require(!points.empty(), "FrameCloud: a frame needs at least one point");
}

std::vector<uint32_t> subsample_indices(size_t n, size_t max_points, uint64_t seed,
                                        uint32_t stream) {
  require(n < size_t(std::numeric_limits<uint32_t>::max()),
          "subsample_indices: too many points (" + std::to_string(n) + ")");
  std::vector<uint32_t> idx(n);
  std::iota(idx.begin(), idx.end(), 0u);
  if (max_points == 0 || max_points >= n) return idx;
  // Partial Fisher-Yates: position k takes a uniform pick among the n − k not yet taken.
  Rng rng(seed, stream);
  for (size_t k = 0; k < max_points; ++k) {
    const size_t pick = k + rng.below(uint32_t(n - k));
    std::swap(idx[k], idx[pick]);
  }
  idx.resize(max_points);
  std::sort(idx.begin(), idx.end());
  return idx;
}

std::vector<geometry::Point3f> subsample_points(const std::vector<Eigen::Vector3f>& scan,
                                                size_t max_points, uint64_t seed,
                                                uint32_t stream) {
  std::vector<geometry::Point3f> out;
  for (uint32_t i : subsample_indices(scan.size(), max_points, seed, stream))
    out.push_back(scan[i]);
  return out;
}

std::vector<geometry::Point3f> subsample_points(const std::vector<PointXYZI>& scan,
                                                size_t max_points, uint64_t seed,
                                                uint32_t stream) {
  std::vector<geometry::Point3f> out;
  for (uint32_t i : subsample_indices(scan.size(), max_points, seed, stream))
    out.emplace_back(scan[i].x, scan[i].y, scan[i].z);
  return out;
}

std::vector<FrameCloud> make_frame_clouds(const std::vector<std::vector<PointXYZI>>& scans,
                                          size_t max_points, uint64_t seed,
                                          const NormalOptions* normals) {
  std::vector<FrameCloud> clouds;
  clouds.reserve(scans.size());
  for (size_t k = 0; k < scans.size(); ++k) {
    require(!scans[k].empty(), "make_frame_clouds: scan " + std::to_string(k) + " is empty");
    clouds.emplace_back(subsample_points(scans[k], max_points, seed, uint32_t(k)));
    if (normals) {
      std::vector<geometry::Point3f> all;
      all.reserve(scans[k].size());
      for (const auto& p : scans[k]) all.emplace_back(p.x, p.y, p.z);
      clouds.back().normals = estimate_normals(clouds.back().points, all, *normals);
    }
  }
  return clouds;
}

}  // namespace sgnlf::posegraph
