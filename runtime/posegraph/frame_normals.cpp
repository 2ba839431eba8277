// Normals by local PCA (see frame_normals.hpp).
#include "posegraph/frame_normals.hpp"

#include <Eigen/Eigenvalues>
#include <string>

#include "core/error.hpp"

namespace sgnlf::posegraph {

void NormalOptions::validate() const {
  require(radius_m > 0.0 && radius_m < 100.0,
          "NormalOptions: radius_m must be in (0, 100), got " + std::to_string(radius_m));
  require(min_neighbours >= 3,
          "NormalOptions: min_neighbours must be >= 3, got " + std::to_string(min_neighbours));
  require(max_flatness > 0.0 && max_flatness <= 1.0,
          "NormalOptions: max_flatness must be in (0, 1], got " + std::to_string(max_flatness));
}

std::vector<geometry::Point3f> estimate_normals(const std::vector<geometry::Point3f>& points,
                                                const std::vector<geometry::Point3f>& scan,
                                                const NormalOptions& o) {
  o.validate();
  require(!scan.empty(), "estimate_normals: empty scan");
  const geometry::KdTree tree(scan);
  std::vector<geometry::Point3f> normals(points.size(), geometry::Point3f::Zero());
  std::vector<uint32_t> near;
  for (size_t k = 0; k < points.size(); ++k) {
    tree.radius_search(points[k], float(o.radius_m), near);
    if (int(near.size()) < o.min_neighbours) continue;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (uint32_t i : near) mean += scan[i].cast<double>();
    mean /= double(near.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (uint32_t i : near) {
      const Eigen::Vector3d d = scan[i].cast<double>() - mean;
      cov += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);  // ascending eigenvalues
    const Eigen::Vector3d lambda = eig.eigenvalues();
    if (!(lambda(1) > 0.0) || lambda(0) > o.max_flatness * lambda(1)) continue;
    Eigen::Vector3d n = eig.eigenvectors().col(0);
    if (n.dot(points[k].cast<double>()) > 0.0) n = -n;
    normals[k] = n.normalized().cast<float>();
  }
  return normals;
}

}  // namespace sgnlf::posegraph
