// k-d tree against a brute-force nearest-neighbour reference (ties, duplicates, degenerate
// splits) and its input validation.
#include <catch2/catch.hpp>

#include <limits>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "geometry/kdtree.hpp"
#include "support/cloud_reference.hpp"

using namespace sgnlf;
using namespace sgnlf::geometry;

using test::brute_nearest;
using test::random_cloud;

TEST_CASE("k-d tree nearest neighbour equals brute force on random clouds", "[geometry][kdtree]") {
  Rng rng(11);
  for (size_t n : {1u, 2u, 13u, 500u, 3000u}) {
    auto pts = random_cloud(rng, n, 40.f);
    // Duplicates and a flat cluster stress ties and degenerate splits.
    for (size_t i = 0; i < n / 10; ++i) pts.push_back(pts[i]);
    for (int i = 0; i < 30; ++i) pts.push_back(Point3f(1.f, 2.f, float(i) * 0.01f));
    const KdTree tree(pts, 4);
    const auto queries = random_cloud(rng, 400, 45.f);
    for (const auto& q : queries) {
      uint32_t idx = 0;
      const float d = tree.nearest(q, &idx);
      REQUIRE(d == brute_nearest(pts, q));
      REQUIRE(squared_distance(q, pts[idx]) == d);
    }
    // Querying the tree's own points gives 0.
    for (size_t i = 0; i < pts.size(); i += 7) REQUIRE(tree.nearest(pts[i]) == 0.f);
  }
}

TEST_CASE("k-d tree rejects empty trees and non-finite points", "[geometry][kdtree]") {
  const KdTree empty(std::vector<Point3f>{});
  CHECK_THROWS_AS(empty.nearest(Point3f::Zero()), Error);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  CHECK_THROWS_AS(KdTree({Point3f(0, 0, 0), Point3f(nan, 0, 0)}), Error);
  const KdTree one({Point3f(1, 1, 1)});
  CHECK_THROWS_AS(one.nearest(Point3f(nan, 0, 0)), Error);
}

TEST_CASE("k-d tree radius search equals a brute-force scan", "[geometry][kdtree]") {
  Rng rng(12);
  for (size_t n : {1u, 2u, 13u, 500u, 3000u}) {
    auto pts = random_cloud(rng, n, 40.f);
    for (size_t i = 0; i < n / 10; ++i) pts.push_back(pts[i]);  // duplicates
    for (int i = 0; i < 30; ++i) pts.push_back(Point3f(1.f, 2.f, float(i) * 0.01f));
    const KdTree tree(pts, 4);
    const auto queries = random_cloud(rng, 200, 45.f);
    std::vector<uint32_t> got;
    for (float r : {0.f, 0.5f, 3.f, 12.f, 100.f}) {
      for (size_t k = 0; k < queries.size() + 20; ++k) {
        // Queries at the tree's own points too (radius 0 must return them and their copies).
        const Point3f q = k < queries.size() ? queries[k] : pts[(k * 37) % pts.size()];
        tree.radius_search(q, r, got);
        std::vector<uint32_t> want;
        for (uint32_t i = 0; i < pts.size(); ++i)
          if (squared_distance(q, pts[i]) <= r * r) want.push_back(i);
        REQUIRE(got == want);
      }
    }
  }
  // A point exactly on the sphere is included.
  const KdTree line({Point3f(0, 0, 0), Point3f(2, 0, 0), Point3f(4, 0, 0)}, 1);
  std::vector<uint32_t> got;
  line.radius_search(Point3f(0, 0, 0), 2.f, got);
  CHECK(got == std::vector<uint32_t>{0, 1});
}

TEST_CASE("k-d tree radius search rejects bad queries", "[geometry][kdtree]") {
  std::vector<uint32_t> out;
  CHECK_THROWS_AS(KdTree(std::vector<Point3f>{}).radius_search(Point3f::Zero(), 1.f, out), Error);
  const KdTree one({Point3f(1, 1, 1)});
  const float nan = std::numeric_limits<float>::quiet_NaN();
  CHECK_THROWS_AS(one.radius_search(Point3f(nan, 0, 0), 1.f, out), Error);
  CHECK_THROWS_AS(one.radius_search(Point3f::Zero(), -1.f, out), Error);
  CHECK_THROWS_AS(one.radius_search(Point3f::Zero(), nan, out), Error);
}
