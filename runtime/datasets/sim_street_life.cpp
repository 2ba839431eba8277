// Opt-in street life of the real-like twins (see sim_street.hpp): vegetation that is not a box
// and pedestrians. Draws from Rng(seed, 3) and Rng(seed, 4), streams no other part uses.
#include <algorithm>
#include <cmath>

#include "core/rng.hpp"
#include "datasets/sim_street.hpp"

namespace sgnlf::sim {

void add_vegetation(StreetWorld& w, uint64_t seed) {
  Rng rng(seed, 3);
  const double wr = w.road_half_width, sw = w.sidewalk_width, L = w.path.length();
  for (int side = -1; side <= 1; side += 2) {
    for (double s = rng.uniform(0.f, 10.f); s < L; s += rng.uniform(6.f, 22.f)) {
      const bool hedge = rng.uniform() < 0.5f;
      const int blobs = hedge ? 3 + int(rng.below(6)) : 1 + int(rng.below(3));
      const double lat0 = side * (wr + sw + rng.uniform(0.2f, 0.9f));  // back of the sidewalk
      double along = 0;
      for (int b = 0; b < blobs; ++b) {
        const float rx = rng.uniform(0.45f, 1.0f), ry = rng.uniform(0.4f, 0.8f), rz = rng.uniform(0.35f, 0.9f);
        const float dz = rng.uniform(0.f, 0.3f), jitter = rng.uniform(-0.25f, 0.25f), refl = rng.uniform(0.15f, 0.35f);
        const double ss = s + along;
        const Eigen::Vector2d c = w.path.point(ss) + w.path.left(ss) * (lat0 + jitter);
        along += 0.9 * rx + 0.3;
        // Round shapes keep their footprint clear of the road (like the trees of sim_street.cpp).
        if (w.path.distance(c) - std::max(rx, ry) < wr + 0.3) continue;
        w.scene.add(Primitive::make_ellipsoid(V3(float(c.x()), float(c.y()), rz * 0.7f + dz), V3(rx, ry, rz),
                                              Material::foliage, refl));
      }
    }
  }
}

void add_pedestrians(StreetWorld& w, int count, uint64_t seed) {
  Rng rng(seed, 4);
  const double wr = w.road_half_width, sw = w.sidewalk_width;
  for (int i = 0; i < count; ++i) {
    Pedestrian p;
    const double side = (i % 2 == 0) ? 1.0 : -1.0;
    const float speed = rng.uniform(0.8f, 1.6f), dir = rng.uniform();
    p.speed = dir < 0.5f ? speed : -speed;
    p.s0 = w.ego_start_s + rng.uniform(-10.f, 120.f);
    p.lateral = side * (wr + rng.uniform(0.6f, float(std::max(0.7, sw - 0.5))));
    p.radius = rng.uniform(0.2f, 0.3f);
    p.height = rng.uniform(1.5f, 1.9f);
    p.reflectance = rng.uniform(0.08f, 0.5f);
    w.walkers.push_back(p);
  }
}

}  // namespace sgnlf::sim
