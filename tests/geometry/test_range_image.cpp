#include <catch2/catch.hpp>

#include <cmath>

#include "core/rng.hpp"
#include "geometry/range_image.hpp"

using namespace sgnlf;

TEST_CASE("pixel directions follow protocol §1", "[range_image]") {
  const Sensor s = sensor_preset("kitti360");
  // Column W/2 looks along +x (β = 0); row 0 is at fov_up.
  const auto d = pixel_direction(s, 0, s.width / 2);
  CHECK(std::atan2(d.z(), std::hypot(d.x(), d.y())) == Approx(2.0 * M_PI / 180).margin(1e-6));
  CHECK(d.y() == Approx(0).margin(1e-6));
  CHECK(d.x() > 0);
  // Column 0 looks along −x (β = π).
  CHECK(pixel_direction(s, 10, 0).x() < 0);
}

TEST_CASE("projection round trip: every pixel ray comes back to its pixel", "[range_image]") {
  for (const char* name : {"kitti360", "nuscenes"}) {
    const Sensor s = sensor_preset(name);
    RangeImage img(s.height, s.width);
    Rng rng(9);
    for (size_t i = 0; i < img.size(); ++i) {
      if (rng.uniform() < 0.2f) continue;
      img.range[i] = rng.uniform(2.0f, 79.0f);
      img.intensity[i] = rng.uniform();
      img.ray_drop[i] = 1.f;
    }
    ProjectionStats st;
    const auto back = project_points(s, unproject(s, img), &st);
    // Column 0 (β = π) maps to c = 0 or W depending on the atan2 branch; the peers drop c = W.
    size_t mismatched = 0;
    for (size_t i = 0; i < img.size(); ++i)
      if (std::fabs(back.range[i] - img.range[i]) > 1e-3f * img.range[i]) ++mismatched;
    INFO(name);
    CHECK(mismatched <= size_t(s.height));
    CHECK(st.occluded == 0);
  }
}

TEST_CASE("projection keeps the nearest return and counts drops", "[range_image]") {
  const Sensor s = sensor_preset("kitti360");
  std::vector<PointXYZI> pts = {{10, 0, -1, 0.5f}, {5, 0, -0.5f, 0.25f}, {90, 0, 0, 1},
                                {NAN, 0, 0, 0},    {0, 0, 50, 0}};
  ProjectionStats st;
  const auto img = project_points(s, pts, &st);
  CHECK(st.occluded == 1);
  CHECK(st.beyond_range == 1);
  CHECK(st.non_finite == 1);
  CHECK(st.out_of_fov == 1);
  float best = 0;
  for (float r : img.range) best = std::max(best, r);
  CHECK(best == Approx(std::sqrt(25.0 + 0.25)));
}
