// The local map's nearest-neighbour search against a brute-force reference over its stored
// points (exact within one voxel size, never closer than the truth beyond it; uncapped and
// capped, near and far from the origin), the float storage's rounding, voxel downsampling, the
// per-voxel cap and the removal of far voxels.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "core/rng.hpp"
#include "odometry/voxel_map.hpp"

using namespace sgnlf;
using namespace sgnlf::odometry;

namespace {

Cloud random_points(Rng& rng, size_t n, double extent) {
  Cloud c(n);
  for (auto& p : c)
    p = Point3(rng.uniform_double() * 2 - 1, rng.uniform_double() * 2 - 1,
               0.2 * (rng.uniform_double() * 2 - 1)) * extent;
  return c;
}

double brute_nearest(const Cloud& pts, const Point3& q) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : pts) best = std::min(best, (p - q).squaredNorm());
  return best;
}

// Compares map.nearest with a brute-force search over the map's stored (float-rounded) points:
// exact whenever the truth lies within one voxel (up to the rounding of a sum of three squares,
// whose order may differ: 1e-12 relative, far below any second-nearest point's distance).
void check_against_brute_force(const VoxelHashMap& map, const Cloud& queries) {
  const auto same = [](double a, double b) { return std::abs(a - b) <= 1e-12 * b; };
  const Cloud stored = map.points();
  REQUIRE(stored.size() == map.num_points());
  const double v = map.voxel_size();
  int exact = 0, beyond = 0;
  for (const auto& q : queries) {
    const double truth = brute_nearest(stored, q);
    Point3 p;
    double d2 = -1;
    const bool found = map.nearest(q, p, d2);
    if (truth <= v * v) {
      REQUIRE(found);
      CHECK(same(d2, truth));
      CHECK(same((p - q).squaredNorm(), d2));
      ++exact;
    } else {
      if (found) CHECK((d2 >= truth || same(d2, truth)));
      ++beyond;
    }
  }
  CHECK(exact > int(queries.size()) / 4);  // the comparison covered many queries
  CHECK(beyond > 0);
}

}  // namespace

TEST_CASE("voxel map nearest neighbour agrees with brute force within one voxel", "[odometry]") {
  Rng rng(7);
  VoxelHashMap map(0.8, 1000, 1e6);  // no cap: every point is stored
  const Cloud pts = random_points(rng, 5000, 20.0);
  map.add_points(pts);
  REQUIRE(map.num_points() == pts.size());
  check_against_brute_force(map, random_points(rng, 2000, 22.0));
  // Float storage: every input point is stored within float rounding (2^-24 relative).
  for (const auto& q : pts) {
    Point3 p;
    double d2;
    REQUIRE(map.nearest(q, p, d2));
    CHECK(std::sqrt(d2) <= 1e-7 * q.norm());
  }
}

TEST_CASE("capped voxel map agrees with brute force over its stored points", "[odometry]") {
  // The odometry's setting: 20 points per 0.8 m voxel (many voxels full), and a map far from
  // the origin, where float rounding is largest.
  Rng rng(8);
  VoxelHashMap map(0.8, 20, 1e6);
  Cloud pts = random_points(rng, 40000, 5.0);
  for (auto& p : pts) p += Point3(700.0, -400.0, 30.0);
  map.add_points(pts);
  REQUIRE(map.num_points() < pts.size() / 2);
  Cloud queries = random_points(rng, 2000, 8.0);
  for (auto& q : queries) q += Point3(700.0, -400.0, 30.0);
  check_against_brute_force(map, queries);
}

TEST_CASE("voxel downsampling keeps the first point of every voxel", "[odometry]") {
  const Cloud pts = {{0.1, 0.1, 0.1}, {0.2, 0.2, 0.2}, {1.1, 0.1, 0.1}, {-0.1, 0.1, 0.1}, {1.9, 0.9, 0.5}};
  const Cloud ds = voxel_downsample(pts, 1.0);
  REQUIRE(ds.size() == 3);
  CHECK(ds[0] == pts[0]);
  CHECK(ds[1] == pts[2]);
  CHECK(ds[2] == pts[3]);
  const Cloud cropped = crop_range({{0.5, 0, 0}, {3, 0, 0}, {100, 0, 0}, {NAN, 0, 0}}, 1.0, 80.0);
  REQUIRE(cropped.size() == 1);
  CHECK(cropped[0].x() == 3.0);
}

TEST_CASE("voxel map caps points per voxel and drops far voxels", "[odometry]") {
  VoxelHashMap map(1.0, 3, 10.0);
  Cloud same_voxel;
  for (int k = 0; k < 10; ++k) same_voxel.emplace_back(0.5, 0.5, 0.05 * k);
  map.add_points(same_voxel);
  CHECK(map.num_voxels() == 1);
  CHECK(map.num_points() == 3);
  map.add_points({{20.5, 0.5, 0.5}});
  CHECK(map.num_voxels() == 2);
  map.remove_far(Point3(0, 0, 0));
  CHECK(map.num_voxels() == 1);
  Point3 p;
  double d2;
  CHECK(map.nearest(Point3(0.5, 0.5, 0.0), p, d2));
  CHECK_FALSE(map.nearest(Point3(20.5, 0.5, 0.5), p, d2));
}
