// The evaluation-time view rules (pipeline/model/view_rules.hpp): GS-LiDAR's "mix" depth and
// the drop of returns the sensor cannot report, on hand-made images against hand-computed
// expectations.
#include <catch2/catch.hpp>

#include "core/error.hpp"
#include "pipeline/model/view_rules.hpp"

using namespace sgnlf;
using namespace sgnlf::pipeline;

TEST_CASE("mix depth: the median only where the variance exceeds 10x the frame's median") {
  RangeImage img(1, 5);
  img.range = {10.f, 20.f, 30.f, 40.f, 50.f};
  img.ray_drop = {1.f, 1.f, 1.f, 0.f, 1.f};
  DepthStats st;
  st.median_m = {11.f, 21.f, 31.f, 41.f, 51.f};
  st.opacity = {1.f, 1.f, 1.f, 1.f, 1.f};
  // Median variance 0.2 (sorted: 0.1, 0.1, 0.2, 2.0, 5.0): threshold 2.0, strictly above it
  // only 5.0; 2.0 itself is not above.
  st.variance_m2 = {0.1f, 5.0f, 0.2f, 2.0f, 0.1f};
  CHECK(mix_variance_threshold(st.variance_m2) == Approx(10.0 * double(0.2f)));
  RangeImage mixed = img;
  CHECK(apply_mix_depth(mixed, st) == 1);
  CHECK(mixed.range == std::vector<float>{10.f, 21.f, 30.f, 40.f, 50.f});
  CHECK(mixed.ray_drop == img.ray_drop);
  CHECK(mixed.intensity == img.intensity);
  // Idempotent: a mixed image mixed again is the same image.
  RangeImage again = mixed;
  apply_mix_depth(again, st);
  CHECK(again.range == mixed.range);
  // Statistics of another image are refused with both sizes named.
  DepthStats small = st;
  small.median_m.pop_back();
  CHECK_THROWS_WITH(apply_mix_depth(mixed, small),
                    Catch::Contains("4 pixels") && Catch::Contains("image of 5"));
  CHECK_THROWS_AS(mix_variance_threshold({}), Error);
}

TEST_CASE("returns the sensor cannot report become drops; drops and in-range returns stay") {
  Sensor s;
  s.min_range_m = 1.8, s.max_range_m = 80.0;
  RangeImage img(1, 6);
  img.range = {1.0f, 1.8f, 1.9f, 79.9f, 80.0f, 90.0f};
  img.ray_drop = {0.9f, 0.6f, 0.7f, 0.8f, 0.51f, 0.2f};
  RangeImage out = img;
  CHECK(drop_out_of_range(out, s) == 3);  // 1.0 and 1.8 (≤ min), 80.0 (≥ max); 90 m already a drop
  CHECK(out.ray_drop == std::vector<float>{0.f, 0.f, 0.7f, 0.8f, 0.f, 0.2f});
  CHECK(out.range == img.range);  // the depth is kept; the mask decides
  s.min_range_m = 0.0, s.max_range_m = 1e4;
  RangeImage all = img;
  CHECK(drop_out_of_range(all, s) == 0);
  CHECK(all.ray_drop == img.ray_drop);
}
