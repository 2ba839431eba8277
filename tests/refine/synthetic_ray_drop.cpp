// synthetic_ray_drop (synthetic_ray_drop.hpp).
#include "synthetic_ray_drop.hpp"

#include <algorithm>
#include <cmath>

#include "core/rng.hpp"

namespace sgnlf::test {

RayDropFrames synthetic_ray_drop(int n, int h, int w, uint64_t seed) {
  RayDropFrames f{n, h, w, {}, {}};
  f.inputs.resize(size_t(n) * h * w * 3);
  f.masks.resize(size_t(n) * h * w);
  Rng rng(seed);
  for (int k = 0; k < n; ++k) {
    const double phase = rng.uniform(0.0f, 6.3f), far_x = rng.uniform(0.0f, float(w));
    const int obj_x = int(rng.below(uint32_t(w / 2))), obj_w = 4 + int(rng.below(uint32_t(w / 4)));
    const int obj_y = int(rng.below(uint32_t(h / 2)));
    std::vector<float> depth(size_t(h) * w);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        // A ground-like ramp, a far band (beyond 60 m) and one near object.
        double d = 8.0 + 40.0 * double(y) / h + 10.0 * std::sin(0.2 * x + phase);
        if (std::fabs(x - far_x) < w / 8.0 && y < h / 2) d = 70.0;
        if (x >= obj_x && x < obj_x + obj_w && y >= obj_y) d = 6.0;
        depth[size_t(y) * w + x] = float(d);
      }
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t p = (size_t(k) * h + y) * w + x;
        const float d = depth[size_t(y) * w + x];
        const float inten = float(0.5 + 0.45 * std::sin(0.35 * x + 0.7 * y + 2.0 * phase));
        bool edge = false;
        for (int dx : {-1, 1}) {
          const int xx = std::clamp(x + dx, 0, w - 1);
          edge = edge || std::fabs(depth[size_t(y) * w + xx] - d) > 4.0f;
        }
        const bool ret = inten >= 0.3f && d <= 60.0f && !edge;
        const float noise = rng.uniform(-0.15f, 0.15f);
        const float prob = float(1.0 / (1.0 + std::exp(-12.0 * (inten - 0.3)))) + noise;
        f.inputs[p * 3 + 0] = std::clamp(prob, 0.01f, 0.99f);
        f.inputs[p * 3 + 1] = inten;
        f.inputs[p * 3 + 2] = d;
        f.masks[p] = ret ? 1.0f : 0.0f;
      }
  }
  return f;
}

double mean_bce(const std::vector<float>& probs, const std::vector<float>& masks) {
  double s = 0;
  for (size_t i = 0; i < probs.size(); ++i) {
    const double p = std::clamp(double(probs[i]), 1e-7, 1.0 - 1e-7);
    s -= masks[i] > 0.5f ? std::log(p) : std::log(1.0 - p);
  }
  return s / double(probs.size());
}

double accuracy(const std::vector<float>& probs, const std::vector<float>& masks) {
  size_t ok = 0;
  for (size_t i = 0; i < probs.size(); ++i) ok += (probs[i] > 0.5f) == (masks[i] > 0.5f);
  return double(ok) / double(probs.size());
}

std::vector<float> input_probability(const RayDropFrames& f) {
  std::vector<float> p(f.masks.size());
  for (size_t i = 0; i < p.size(); ++i) p[i] = f.inputs[i * 3];
  return p;
}

}  // namespace sgnlf::test
