// The baked scene's ray caster (kernels/bake/raycast.cl) against its host reference
// (raycast_reference.hpp) on the analytic scene: rays from inside and outside the brick grid,
// along the axes (zero direction components), through bricks and empty space; then physical
// checks: the wall's depth, early termination, rays that miss.
#include <catch2/catch.hpp>

#include <cmath>

#include "bake/ray_caster.hpp"
#include "bake_test_scene.hpp"
#include "raycast_reference.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {

const bake::BakedScene& scene() {
  static const bake::BakedScene s =
      bake::bake_field(test::test_scene_config(), test::test_scene_input(), test::test_scene_probe());
  return s;
}

// n rays: origins around the sensor origins and beyond the grid, directions over the sphere,
// a few along the axes.
void make_rays(int n, std::vector<float>& o, std::vector<float>& d) {
  const auto u = test::uniform(size_t(n) * 6, -1.0f, 1.0f, 7);
  o.resize(size_t(n) * 3), d.resize(size_t(n) * 3);
  for (int i = 0; i < n; ++i) {
    float v[3] = {u[6 * size_t(i) + 3], u[6 * size_t(i) + 4], 0.3f * u[6 * size_t(i) + 5]};
    if (i % 17 == 0) v[0] = 1.0f, v[1] = 0.0f, v[2] = 0.0f;        // along +x: into the wall
    if (i % 17 == 1) v[0] = 0.0f, v[1] = 0.0f, v[2] = -1.0f;       // straight down
    if (i % 17 == 2) v[0] = 0.0f, v[1] = -1.0f, v[2] = 0.0f;       // along the wall
    const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const float scale = i % 5 == 4 ? 20.0f : 2.0f;  // every fifth from far outside the grid
    for (int a = 0; a < 3; ++a) {
      o[3 * size_t(i) + size_t(a)] = scale * u[6 * size_t(i) + size_t(a)];
      d[3 * size_t(i) + size_t(a)] = v[a] / len;
    }
  }
}

}  // namespace

TEST_CASE("baked ray caster matches the host reference", "[bake][raycast]") {
  const bake::BakedScene& s = scene();
  const int n = 1500;
  std::vector<float> o, d;
  make_rays(n, o, d);
  bake::RayCaster caster(test::runtime(), s);
  const std::vector<float> got = caster.cast(o, d);
  constexpr size_t K = bake::RayCaster::kOutputs;
  REQUIRE(got.size() == size_t(n) * K);
  std::vector<float> want(got.size());
  for (int i = 0; i < n; ++i) {
    const auto r = test::raycast_reference(s, &o[3 * size_t(i)], &d[3 * size_t(i)]);
    for (size_t c = 0; c < K; ++c) want[K * size_t(i) + c] = r[c];
  }
  // Float math in a different order (fma, exp): compared per channel with an absolute floor
  // (depth in metres, probabilities in [0, 1]); a ray whose early termination lands one sample
  // apart moves by at most that sample's tiny weight, a quartile level crossed one sample apart
  // by one step.
  long hits = 0, quartiles = 0, quartiles_equal = 0;
  for (int i = 0; i < n; ++i) {
    INFO("ray " << i);
    const float* g = &got[K * size_t(i)];
    const float* w = &want[K * size_t(i)];
    CHECK(g[0] == Approx(w[0]).epsilon(1e-4).margin(2e-3));
    for (size_t c = 1; c < 4; ++c) CHECK(g[c] == Approx(w[c]).margin(2e-4));
    CHECK(g[8] == Approx(w[8]).epsilon(1e-4).margin(s.step_m * 1.01f));  // the median's sample
    CHECK(g[9] == Approx(w[9]).epsilon(1e-3).margin(2e-3));              // variance, m²
    for (size_t c = 4; c < 8; ++c) {
      CHECK((g[c] < 0.0f) == (w[c] < 0.0f));
      CHECK(g[c] == Approx(w[c]).margin(s.step_m * 1.01f));
      quartiles += w[c] >= 0.0f;
      quartiles_equal += w[c] >= 0.0f && g[c] == w[c];
    }
    // The quartiles are sample depths in order, within the ray's weight.
    for (size_t c = 5; c < 8; ++c)
      if (g[c] >= 0.0f) CHECK(g[c] >= g[c - 1]);
    // The median lies between the 3/8 and 5/8 quartiles' samples.
    if (g[6] >= 0.0f) {
      CHECK(g[8] >= g[5] - 1e-4f);
      CHECK(g[8] <= g[6] + s.step_m);
    }
    hits += w[1] > 0.5f;
  }
  CHECK(quartiles > n);                       // levels reached on the rays that meet surfaces
  CHECK(quartiles_equal > quartiles * 9 / 10);  // and nearly all on the same sample
  CHECK(hits > n / 4);      // the rays meet the surfaces
  CHECK(hits < n * 9 / 10);  // and some leave the scene
  // Deterministic: the same bits again.
  CHECK(caster.cast(o, d) == got);
}

TEST_CASE("baked ray caster: the wall's depth, its attributes, early termination, misses",
          "[bake][raycast]") {
  const bake::BakedScene& s = scene();
  bake::RayCaster caster(test::runtime(), s);
  // Along +x from the origin: the wall at 6 m (σ rises over ~0.1 m behind it), opaque.
  const std::vector<float> o{0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f},
      d{1.0f, 0.0f, 0.0f, -1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f};
  const std::vector<float> r = caster.cast(o, d);
  constexpr size_t K = bake::RayCaster::kOutputs;
  CHECK(r[0] == Approx(6.0f).margin(0.15f));
  CHECK(r[1] == Approx(0.85f).margin(0.01f));              // the head's return probability
  CHECK(r[2] == Approx(0.5f + 0.1f).margin(0.02f));        // its intensity at y = 0, seen along +x
  CHECK(r[3] == Approx(1.0f).margin(1e-3f));  // opaque
  // Its weight's quartiles: in order, around the depth, within the ~0.1 m the σ rises over.
  for (size_t c = 4; c < 8; ++c) {
    CHECK(r[c] == Approx(6.0f).margin(0.2f));
    if (c > 4) CHECK(r[c] >= r[c - 1]);
  }
  CHECK(r[7] - r[4] < 0.25f);
  CHECK(r[4] <= r[0] + s.step_m);
  CHECK(r[7] >= r[0] - s.step_m);
  // The median where T falls to 1/2, near the depth; the variance of a sharp wall, small.
  CHECK(r[8] == Approx(r[0]).margin(0.1f));
  CHECK(r[8] >= r[5] - 1e-4f);
  CHECK(r[8] <= r[6] + s.step_m);
  CHECK(r[9] >= 0.0f);
  CHECK(r[9] < 0.01f);
  // Away from the wall and up: nothing stored there, no quartile reached.
  CHECK(r[K] == 0.0f);
  CHECK(r[K + 1] == 0.0f);
  CHECK(r[K + 3] == 0.0f);
  CHECK(r[K + 4] == -1.0f);
  CHECK(r[K + 7] == -1.0f);
  CHECK(r[K + 9] == 0.0f);
  CHECK(r[2 * K + 1] == 0.0f);
  // Early termination: the reference with and without a stop gives the same depth to 1e-3.
  bake::BakedScene no_stop = s;
  no_stop.stop_transmittance = 0.0f;
  const auto full = test::raycast_reference(no_stop, o.data(), d.data());
  CHECK(full[0] == Approx(r[0]).margin(1e-3f * 6.0f + 1e-3f));
}
