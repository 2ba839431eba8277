// head_rows (see head_rows.hpp).
#include "bake/head_rows.hpp"

#include "bake/ray_caster.hpp"
#include "core/error.hpp"

namespace sgnlf::bake {

std::vector<HeadRow> head_rows(const std::vector<float>& cast, size_t n, float spread_m,
                               long* spread_rays) {
  constexpr size_t K = RayCaster::kOutputs;
  require(cast.size() >= n * K, "head_rows: the cast holds fewer than n rays");
  std::vector<HeadRow> rows;
  rows.reserve(n);
  for (size_t p = 0; p < n; ++p) {
    const float* r = &cast[K * p];
    const float opacity = r[3];
    if (!(opacity > 1e-4f)) continue;
    int reached = 0;
    while (reached < 4 && r[4 + reached] >= 0.0f) ++reached;
    if (reached < 2 || r[4 + reached - 1] - r[4] <= spread_m) {
      rows.push_back({p, r[0] / opacity, opacity});
      continue;
    }
    for (int k = 0; k < reached; ++k) rows.push_back({p, r[4 + k], opacity / float(reached)});
    if (spread_rays) ++*spread_rays;
  }
  return rows;
}

}  // namespace sgnlf::bake
