// unit_features (see point_features.hpp).
#include "posegraph/point_features.hpp"

#include <cmath>

#include "core/error.hpp"

namespace sgnlf::posegraph {

std::vector<float> unit_features(const FeatureProvider& f,
                                 const std::vector<Eigen::Vector3f>& x_world) {
  require(bool(f.eval), "pose-graph features: the feature provider is empty");
  require(f.dim >= 1, "pose-graph features: provider '" + f.name + "' has dim " +
                          std::to_string(f.dim) + " (must be >= 1)");
  std::vector<float> out;
  f.eval(x_world, out);
  const size_t want = x_world.size() * size_t(f.dim);
  require(out.size() == want, "pose-graph features: provider '" + f.name + "' returned " +
                                  std::to_string(out.size()) + " values for " +
                                  std::to_string(x_world.size()) + " points of dim " +
                                  std::to_string(f.dim) + " (expected " + std::to_string(want) +
                                  ")");
  std::vector<int> parts = f.parts.empty() ? std::vector<int>{f.dim} : f.parts;
  int sum = 0;
  for (int w : parts) {
    require(w >= 1, "pose-graph features: provider '" + f.name + "' has a part of width " +
                        std::to_string(w) + " (must be >= 1)");
    sum += w;
  }
  require(sum == f.dim, "pose-graph features: provider '" + f.name + "' has parts summing to " +
                            std::to_string(sum) + ", not its dim " + std::to_string(f.dim));
  std::vector<double> norm(parts.size());
  for (size_t r = 0; r < x_world.size(); ++r) {
    float* row = out.data() + r * size_t(f.dim);
    for (int k = 0; k < f.dim; ++k)
      if (!std::isfinite(row[k]))
        throw NumericError("pose-graph features: provider '" + f.name + "' gave a non-finite "
                           "value at point " + std::to_string(r) + ", component " +
                           std::to_string(k));
    int nonzero = 0, begin = 0;
    for (size_t p = 0; p < parts.size(); ++p) {
      double sq = 0.0;
      for (int k = begin; k < begin + parts[p]; ++k) sq += double(row[k]) * double(row[k]);
      norm[p] = std::sqrt(sq);
      nonzero += sq > 0.0 ? 1 : 0;
      begin += parts[p];
    }
    if (nonzero == 0) continue;
    const double part_length = 1.0 / std::sqrt(double(nonzero));
    begin = 0;
    for (size_t p = 0; p < parts.size(); ++p) {
      if (norm[p] > 0.0) {
        const float scale = float(part_length / norm[p]);
        for (int k = begin; k < begin + parts[p]; ++k) row[k] *= scale;
      }
      begin += parts[p];
    }
  }
  return out;
}

}  // namespace sgnlf::posegraph
