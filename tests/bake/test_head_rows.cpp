// Where the baked renderer evaluates the field's LiDAR head (bake/head_rows.hpp): one row at the
// surface point where a ray's weight is tight, a row per quartile reached where it spreads, none
// where the ray meets nothing.
#include <catch2/catch.hpp>

#include <array>
#include <vector>

#include "bake/head_rows.hpp"
#include "bake/ray_caster.hpp"

using namespace sgnlf;

namespace {

// One ray's caster output: depth (Σ w·t), opacity, the four quartile depths.
std::vector<float> ray(float depth, float opacity, std::array<float, 4> q) {
  std::vector<float> r(bake::RayCaster::kOutputs, 0.0f);
  r[0] = depth, r[3] = opacity;
  for (size_t k = 0; k < 4; ++k) r[4 + k] = q[k];
  return r;
}

}  // namespace

TEST_CASE("head rows: one at the surface point, one per quartile where the weight spreads",
          "[bake]") {
  std::vector<float> cast;
  for (const auto& r : {ray(0.0f, 0.0f, {-1, -1, -1, -1}),        // meets nothing
                        ray(9.0f, 0.9f, {9.95f, 9.98f, 10.02f, 10.04f}),  // tight: 0.09 m
                        ray(16.0f, 0.8f, {18.0f, 19.0f, 21.0f, 22.0f}),  // spread over 4 m
                        ray(7.0f, 0.6f, {10.0f, 12.0f, 14.0f, -1}),  // 3 quartiles reached
                        ray(5.0f, 0.2f, {25.0f, -1, -1, -1})})      // 1 reached: the point
    cast.insert(cast.end(), r.begin(), r.end());
  long spread = 0;
  const auto rows = bake::head_rows(cast, 5, 0.1f, &spread);
  REQUIRE(rows.size() == 1 + 4 + 3 + 1);
  CHECK(spread == 2);
  CHECK(rows[0].ray == 1);
  CHECK(rows[0].t_m == Approx(10.0f));
  CHECK(rows[0].weight == Approx(0.9f));
  for (size_t k = 0; k < 4; ++k) {
    CHECK(rows[1 + k].ray == 2);
    CHECK(rows[1 + k].weight == Approx(0.2f));
  }
  CHECK(rows[4].t_m == Approx(22.0f));
  CHECK(rows[5].ray == 3);
  CHECK(rows[7].t_m == Approx(14.0f));
  CHECK(rows[8].ray == 4);
  CHECK(rows[8].t_m == Approx(25.0f));
  // A wide spread takes every ray at its surface point.
  CHECK(bake::head_rows(cast, 5, 100.0f).size() == 4);
  CHECK_THROWS(bake::head_rows(cast, 6, 0.1f));
}
