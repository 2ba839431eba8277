// A small analytic scene baked through bake::bake_field for the bake tests: a wall at x = 6 m
// and a ground at z = −1.5 m (σ logit rising steeply behind each surface), a head whose return
// probability and intensity vary with position and view direction, returns sampled on both
// surfaces, two sensor origins.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "bake/bake.hpp"

namespace sgnlf::test {

// Signed distance (metres) to the nearest of the two surfaces, negative behind them.
inline float test_scene_sdf(float x, float, float z) { return std::min(6.0f - x, z + 1.5f); }

inline bake::FieldProbe test_scene_probe() {
  bake::FieldProbe p;
  p.batch = 5000;  // several calls per bake
  p.density = [](const std::vector<float>& x, int n) {
    std::vector<float> l(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i)
      l[size_t(i)] = std::clamp(2.0f - 25.0f * test_scene_sdf(x[3 * size_t(i)], x[3 * size_t(i) + 1],
                                                               x[3 * size_t(i) + 2]),
                                -20.0f, 12.0f);
    return l;
  };
  p.head = [](const std::vector<float>& x, const std::vector<float>& d, int n) {
    std::vector<float> h(static_cast<size_t>(n) * 2);
    for (int i = 0; i < n; ++i) {
      const float* xi = &x[3 * size_t(i)];
      h[2 * size_t(i)] = 0.85f - 0.1f * std::fabs(d[3 * size_t(i) + 2]);
      h[2 * size_t(i) + 1] = 0.5f + 0.3f * std::sin(0.7f * xi[1]) + 0.1f * d[3 * size_t(i)];
    }
    return h;
  };
  return p;
}

inline bake::BakeInput test_scene_input() {
  bake::BakeInput in;
  for (float y = -6.0f; y <= 6.0f; y += 0.25f) {
    for (float z = -1.5f; z <= 2.0f; z += 0.25f) in.returns_m.insert(in.returns_m.end(), {6.0f, y, z});
    for (float x = -2.0f; x <= 6.0f; x += 0.25f) in.returns_m.insert(in.returns_m.end(), {x, y, -1.5f});
  }
  in.origins_m = {0.0f, 0.0f, 0.0f, 1.0f, 0.5f, 0.2f};
  in.near_m = 0.5f, in.far_m = 30.0f;
  return in;
}

// Bricks of 4 cells of 0.2 m: a few hundred bricks, fast to bake and cast.
inline bake::BakeConfig test_scene_config() {
  bake::BakeConfig c;
  c.voxel_m = 0.2f;
  c.brick = 4;
  c.dilate_m = 0.3f;
  return c;
}

}  // namespace sgnlf::test
