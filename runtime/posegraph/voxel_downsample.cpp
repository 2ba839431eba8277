// voxel_downsample (see voxel_downsample.hpp).
#include "posegraph/voxel_downsample.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>

#include <Eigen/Core>

#include "core/error.hpp"

namespace sgnlf::posegraph {

VoxelGrid voxel_downsample(const std::vector<geometry::Point3f>& x, double voxel_m) {
  require(std::isfinite(voxel_m) && voxel_m > 0.0,
          "voxel_downsample: voxel size " + std::to_string(voxel_m) + " m (must be > 0)");
  constexpr int64_t kLimit = int64_t(1) << 20;
  VoxelGrid g;
  g.voxel_of.resize(x.size());
  std::unordered_map<uint64_t, uint32_t> index;  // lookup only: never iterated
  std::vector<Eigen::Vector3d> sum;
  std::vector<uint32_t> count;
  for (size_t k = 0; k < x.size(); ++k) {
    require(x[k].allFinite(), "voxel_downsample: point " + std::to_string(k) + " is not finite");
    uint64_t key = 0;
    for (int a = 0; a < 3; ++a) {
      const double c = std::floor(double(x[k][a]) / voxel_m);
      require(std::abs(c) < double(kLimit),
              "voxel_downsample: point " + std::to_string(k) + " lies beyond 2^20 voxels of " +
                  std::to_string(voxel_m) + " m from the origin");
      key = (key << 21) | uint64_t(int64_t(c) + kLimit);
    }
    const auto it = index.emplace(key, uint32_t(sum.size())).first;
    if (it->second == sum.size()) {
      sum.push_back(Eigen::Vector3d::Zero());
      count.push_back(0);
    }
    g.voxel_of[k] = it->second;
    sum[it->second] += x[k].cast<double>();
    ++count[it->second];
  }
  g.representative.assign(sum.size(), 0);
  std::vector<double> best(sum.size(), std::numeric_limits<double>::infinity());
  for (size_t k = 0; k < x.size(); ++k) {
    const uint32_t v = g.voxel_of[k];
    const double d = (x[k].cast<double>() - sum[v] / double(count[v])).squaredNorm();
    if (d < best[v]) {  // strict: ties keep the lowest index
      best[v] = d;
      g.representative[v] = uint32_t(k);
    }
  }
  return g;
}

}  // namespace sgnlf::posegraph
