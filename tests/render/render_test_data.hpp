// Synthetic inputs for the render tests: rays, sorted sample distances, random arrays, all
// from fixed Philox seeds.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/rng.hpp"

namespace sgnlf::test {

// Origins in [-0.5, 0.5]^3 and unit directions.
inline void make_rays(int n, uint64_t seed, std::vector<float>& o, std::vector<float>& d) {
  Rng rng(seed, 11);
  o.resize(size_t(n) * 3);
  d.resize(size_t(n) * 3);
  for (int r = 0; r < n; ++r) {
    double v[3], norm = 0;
    for (int c = 0; c < 3; ++c) {
      o[3 * r + c] = rng.uniform(-0.5f, 0.5f);
      v[c] = rng.normal();
      norm += v[c] * v[c];
    }
    norm = std::sqrt(norm);
    for (int c = 0; c < 3; ++c) d[3 * r + c] = float(v[c] / norm);
  }
}

inline std::vector<float> make_uniform(size_t n, float lo, float hi, uint64_t seed) {
  Rng rng(seed, 12);
  std::vector<float> v(n);
  for (auto& x : v) x = rng.uniform(lo, hi);
  return v;
}

}  // namespace sgnlf::test
