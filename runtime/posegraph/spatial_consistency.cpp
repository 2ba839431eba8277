// spatial_consistency (see spatial_consistency.hpp).
#include "posegraph/spatial_consistency.hpp"

#include <string>

#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf::posegraph {

double spatial_consistency(const std::vector<Vec3>& p, const std::vector<Vec3>& q,
                           double sigma_d, size_t max_pairs, uint64_t seed, uint32_t stream) {
  require(p.size() == q.size(), "spatial_consistency: " + std::to_string(p.size()) +
                                    " points in frame i but " + std::to_string(q.size()) +
                                    " in frame j");
  require(std::isfinite(sigma_d) && sigma_d > 0.0,
          "spatial_consistency: sigma_d " + std::to_string(sigma_d) + " (must be > 0)");
  require(max_pairs > 0, "spatial_consistency: max_pairs must be > 0");
  const size_t n = p.size();
  if (n < 2) return 0.0;
  const double all = 0.5 * double(n) * double(n - 1);
  double sum = 0.0;
  if (all <= double(max_pairs)) {
    for (size_t m = 0; m < n; ++m)
      for (size_t k = m + 1; k < n; ++k) sum += pair_consistency(p[m], p[k], q[m], q[k], sigma_d);
    return sum / all;
  }
  Rng rng(seed, stream);
  for (size_t s = 0; s < max_pairs; ++s) {
    const uint32_t m = rng.below(uint32_t(n));
    uint32_t k = rng.below(uint32_t(n - 1));
    if (k >= m) ++k;
    sum += pair_consistency(p[m], p[k], q[m], q[k], sigma_d);
  }
  return sum / double(max_pairs);
}

}  // namespace sgnlf::posegraph
