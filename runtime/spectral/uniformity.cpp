// χ² cell statistics, chart cells and neighbour-count density thinning (uniformity.hpp).
#include "spectral/uniformity.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/error.hpp"

namespace sgnlf::spectral {

UniformityStats cell_uniformity(const std::vector<int>& cell_of_point, const std::vector<double>& cell_prob) {
  UniformityStats s;
  s.points = cell_of_point.size();
  s.cells = cell_prob.size();
  require(s.cells >= 2 && s.points > 0, "cell_uniformity: need >= 2 cells and some points");
  std::vector<double> count(s.cells, 0.0);
  for (int c : cell_of_point) {
    require(c >= 0 && size_t(c) < s.cells, "cell_uniformity: cell index out of range");
    count[c] += 1;
  }
  double chi2 = 0;
  for (size_t c = 0; c < s.cells; ++c) {
    const double e = cell_prob[c] * double(s.points);
    chi2 += (count[c] - e) * (count[c] - e) / e;
    s.max_rel_dev = std::max(s.max_rel_dev, std::fabs(count[c] - e) / e);
  }
  s.chi2_per_dof = chi2 / double(s.cells - 1);
  s.mean_count = double(s.points) / double(s.cells);
  return s;
}

std::vector<int> chart_cells(const Shape& shape, const ShapeSpec& spec,
                             const std::vector<SurfacePoint>& pts, int nu, int nv,
                             std::vector<double>& cell_prob) {
  cell_prob.assign(size_t(nu) * nv, 1.0 / (double(nu) * nv));
  std::vector<double> vprob(nv, 1.0 / nv);
  if (spec.kind == ShapeKind::torus) {  // ∫ (R + r cos 2πv) dv over the band, normalised
    const double two_pi = 6.283185307179586;
    for (int j = 0; j < nv; ++j) {
      const double a = two_pi * j / nv, b = two_pi * (j + 1) / nv;
      vprob[j] = (spec.major * (b - a) + spec.radius * (std::sin(b) - std::sin(a))) / (two_pi * spec.major);
    }
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) cell_prob[size_t(j) * nu + i] = vprob[j] / nu;
  }
  std::vector<int> cells(pts.size());
  for (size_t p = 0; p < pts.size(); ++p) {
    Eigen::Vector2d uv = shape.chart(pts[p].x);
    if (spec.kind == ShapeKind::sphere) uv.y() = (1 - std::cos(uv.y() * 3.141592653589793)) / 2;
    const int i = std::clamp(int(uv.x() * nu), 0, nu - 1), j = std::clamp(int(uv.y() * nv), 0, nv - 1);
    cells[p] = j * nu + i;
  }
  return cells;
}

std::vector<size_t> thin_to_uniform_density(const std::vector<Eigen::Vector3d>& pts, double radius,
                                            Rng& rng, double quantile) {
  require(radius > 0 && quantile >= 0 && quantile <= 1, "thin_to_uniform_density: bad radius/quantile");
  auto key = [&](const Eigen::Vector3d& x, int dx, int dy, int dz) {
    const int64_t i = int64_t(std::floor(x.x() / radius)) + dx, j = int64_t(std::floor(x.y() / radius)) + dy,
                  k = int64_t(std::floor(x.z() / radius)) + dz;
    // 21 bits per axis: unique keys for |cell index| < 2^20.
    auto b = [](int64_t c) { return uint64_t(c + (int64_t(1) << 20)) & 0x1FFFFFu; };
    return int64_t((b(i) << 42) | (b(j) << 21) | b(k));
  };
  std::unordered_map<int64_t, std::vector<size_t>> grid;
  for (size_t i = 0; i < pts.size(); ++i) grid[key(pts[i], 0, 0, 0)].push_back(i);
  std::vector<double> count(pts.size(), 0.0);
  const double r2 = radius * radius;
  for (size_t i = 0; i < pts.size(); ++i)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find(key(pts[i], dx, dy, dz));
          if (it == grid.end()) continue;
          for (size_t j : it->second) count[i] += (pts[j] - pts[i]).squaredNorm() <= r2;
        }
  std::vector<double> sorted = count;
  const size_t q = std::min(sorted.size() - 1, size_t(quantile * double(sorted.size())));
  std::nth_element(sorted.begin(), sorted.begin() + q, sorted.end());
  const double cq = sorted[q];
  std::vector<size_t> keep;
  for (size_t i = 0; i < pts.size(); ++i)
    if (rng.uniform_double() * count[i] < cq) keep.push_back(i);
  return keep;
}

}  // namespace sgnlf::spectral
