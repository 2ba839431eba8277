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
  for (size_t r = 0; r < x_world.size(); ++r) {
    float* row = out.data() + r * size_t(f.dim);
    double sq = 0.0;
    for (int k = 0; k < f.dim; ++k) {
      if (!std::isfinite(row[k]))
        throw NumericError("pose-graph features: provider '" + f.name + "' gave a non-finite "
                           "value at point " + std::to_string(r) + ", component " +
                           std::to_string(k));
      sq += double(row[k]) * double(row[k]);
    }
    if (sq == 0.0) continue;
    const float inv = float(1.0 / std::sqrt(sq));
    for (int k = 0; k < f.dim; ++k) row[k] *= inv;
  }
  return out;
}

}  // namespace sgnlf::posegraph
