// Surface samples from observed points (method.md §4.1: "observed points under the current
// poses, thinned by rejection sampling to uniform area density"): thin the points to uniform area
// density (uniformity.hpp), then give each kept point a unit normal from the PCA of its
// neighbours within `radius` in the full set (smallest-eigenvalue direction) and two tangents.
// Normals are unoriented; the spectral loss only uses the tangents, so the sign does not matter.
#pragma once
#include <vector>

#include "spectral/surface.hpp"

namespace sgnlf::spectral {

struct PointCloudSurfaceStats {
  size_t input = 0, kept = 0, too_few_neighbours = 0;
};

// Weights 1/kept. Points with fewer than 5 neighbours within `radius` are dropped.
std::vector<SurfacePoint> surface_from_points(const std::vector<Eigen::Vector3d>& pts, double radius, Rng& rng,
                                              PointCloudSurfaceStats* stats = nullptr);

}  // namespace sgnlf::spectral
