// Uniformity of surface samples and thinning of observed point sets to uniform area density
// (method.md §4.1 "observed points ... thinned by rejection sampling to uniform area density").
#pragma once
#include <vector>

#include "spectral/surface.hpp"

namespace sgnlf::spectral {

// Counts of points per cell against expected cell probabilities: Pearson χ²/dof (≈ 1 ± √(2/dof)
// for a uniform sample) and the largest relative deviation of a cell count from its expectation.
struct UniformityStats {
  size_t points = 0, cells = 0;
  double chi2_per_dof = 0, max_rel_dev = 0, mean_count = 0;
};
UniformityStats cell_uniformity(const std::vector<int>& cell_of_point, const std::vector<double>& cell_prob);

// Equal-area cells of a shape via its chart: sphere (bands in cos θ × sectors in φ, equal by
// Archimedes), cylinder and square (uniform chart grid), torus (chart grid, probability
// ∝ ∫(R + r cos θ)). Returns each point's cell and fills cell_prob.
std::vector<int> chart_cells(const Shape& shape, const ShapeSpec& spec,
                             const std::vector<SurfacePoint>& pts, int nu, int nv,
                             std::vector<double>& cell_prob);

// Indices of a thinned subset with approximately uniform area density: the local density is
// the neighbour count within `radius` (voxel hash), and point i is kept with probability
// min(1, c_q / c_i), c_q the `quantile` of the counts (0 = the minimum: uniform up to the
// count noise; a higher quantile keeps more points but under-fills the sparsest regions).
std::vector<size_t> thin_to_uniform_density(const std::vector<Eigen::Vector3d>& pts, double radius,
                                            Rng& rng, double quantile = 0.0);

}  // namespace sgnlf::spectral
