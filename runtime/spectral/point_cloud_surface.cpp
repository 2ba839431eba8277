// Thinning + PCA normals for observed point sets (point_cloud_surface.hpp).
#include "spectral/point_cloud_surface.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <unordered_map>

#include "spectral/uniformity.hpp"

namespace sgnlf::spectral {

std::vector<SurfacePoint> surface_from_points(const std::vector<Eigen::Vector3d>& pts, double radius, Rng& rng,
                                              PointCloudSurfaceStats* stats) {
  PointCloudSurfaceStats st;
  st.input = pts.size();
  const auto keep = thin_to_uniform_density(pts, radius, rng);
  // Voxel hash of the full set (cell = radius) for the neighbourhoods.
  auto cell = [&](const Eigen::Vector3d& x, int dx, int dy, int dz) {
    auto b = [](int64_t c) { return uint64_t(c + (int64_t(1) << 20)) & 0x1FFFFFu; };
    return (b(int64_t(std::floor(x.x() / radius)) + dx) << 42) | (b(int64_t(std::floor(x.y() / radius)) + dy) << 21) |
           b(int64_t(std::floor(x.z() / radius)) + dz);
  };
  std::unordered_map<uint64_t, std::vector<size_t>> grid;
  for (size_t i = 0; i < pts.size(); ++i) grid[cell(pts[i], 0, 0, 0)].push_back(i);
  std::vector<SurfacePoint> out;
  out.reserve(keep.size());
  const double r2 = radius * radius;
  for (size_t i : keep) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    Eigen::Matrix3d m2 = Eigen::Matrix3d::Zero();
    int count = 0;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find(cell(pts[i], dx, dy, dz));
          if (it == grid.end()) continue;
          for (size_t j : it->second) {
            const Eigen::Vector3d d = pts[j] - pts[i];
            if (d.squaredNorm() > r2) continue;
            mean += d;
            m2 += d * d.transpose();
            ++count;
          }
        }
    if (count < 5) {
      ++st.too_few_neighbours;
      continue;
    }
    mean /= count;
    const Eigen::Matrix3d cov = m2 / count - mean * mean.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
    SurfacePoint p;
    p.x = pts[i];
    p.n = es.eigenvectors().col(0).normalized();  // smallest eigenvalue first
    tangent_frame(p.n, p.t1, p.t2);
    out.push_back(p);
  }
  for (auto& p : out) p.w = 1.0 / double(out.size());
  st.kept = out.size();
  if (stats) *stats = st;
  return out;
}

}  // namespace sgnlf::spectral
