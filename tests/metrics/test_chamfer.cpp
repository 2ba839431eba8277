// Chamfer / F-score on cases computed by hand and against a brute-force definition (protocol §4:
// squared distances, τ = 0.05 m² ⇒ √0.05 m effective). The k-d tree itself is tested in
// tests/geometry/test_kdtree.cpp.
#include <catch2/catch.hpp>

#include "support/cloud_reference.hpp"

#include <cmath>
#include <limits>

#include "core/rng.hpp"
#include "metrics/chamfer.hpp"

using namespace sgnlf;
using namespace sgnlf::metrics;
using geometry::Point3f;
using geometry::squared_distance;

using test::brute_nearest;
using test::random_cloud;

TEST_CASE("Chamfer distance and F-score on a hand-computed case", "[metrics][chamfer]") {
  // pred = {0}, gt = {(0.1,0,0), (1,0,0)}: d1 = {0.01}, d2 = {0.01, 1}.
  const std::vector<Point3f> pred = {Point3f(0, 0, 0)};
  const std::vector<Point3f> gt = {Point3f(0.1f, 0, 0), Point3f(1, 0, 0)};
  const auto r = chamfer_fscore(pred, gt);
  const double d01 = double(0.1f) * double(0.1f);
  CHECK(r.cd == Approx(d01 + (d01 + 1.0) / 2.0).epsilon(1e-6));  // ≈ 0.515
  CHECK(r.cd_pred_to_gt == Approx(d01).epsilon(1e-6));
  CHECK(r.cd_gt_to_pred == Approx((d01 + 1.0) / 2.0).epsilon(1e-6));
  CHECK(r.precision == 1.0);
  CHECK(r.recall == 0.5);
  CHECK(r.fscore == Approx(2.0 * 1.0 * 0.5 / 1.5));  // 2/3
  // Symmetric: swapping the sets swaps precision and recall, CD and F unchanged.
  const auto s = chamfer_fscore(gt, pred);
  CHECK(s.cd == Approx(r.cd));
  CHECK(s.cd_pred_to_gt == Approx(r.cd_gt_to_pred));
  CHECK(s.precision == r.recall);
  CHECK(s.fscore == Approx(r.fscore));
}

TEST_CASE("F-score threshold acts on squared distances (effective sqrt(0.05) m)",
          "[metrics][chamfer]") {
  const std::vector<Point3f> gt = {Point3f(10, 0, 0)};
  // 0.2 m apart: 0.04 m² < 0.05 → counted; a "5 cm" threshold would reject it.
  CHECK(chamfer_fscore({Point3f(10.2f, 0, 0)}, gt).fscore == 1.0);
  // 0.23 m apart: 0.0529 m² ≥ 0.05 → rejected.
  const auto far = chamfer_fscore({Point3f(10.23f, 0, 0)}, gt);
  CHECK(far.fscore == 0.0);
  CHECK(far.cd == Approx(2 * 0.0529).epsilon(1e-4));
}

TEST_CASE("Chamfer: empty sets give NaN CD and zero F-score", "[metrics][chamfer]") {
  const auto r = chamfer_fscore({}, {Point3f(1, 0, 0)});
  CHECK(std::isnan(r.cd));
  CHECK(r.fscore == 0.0);
  CHECK(r.n_gt == 1);
}

TEST_CASE("Chamfer via k-d tree equals the brute-force definition", "[metrics][chamfer]") {
  Rng rng(3);
  const auto a = random_cloud(rng, 1500, 5.f);
  const auto b = random_cloud(rng, 1100, 5.f);
  double s1 = 0, s2 = 0;
  size_t c1 = 0, c2 = 0;
  for (const auto& p : a) {
    const float d = brute_nearest(b, p);
    s1 += d;
    c1 += d < 0.05;
  }
  for (const auto& p : b) {
    const float d = brute_nearest(a, p);
    s2 += d;
    c2 += d < 0.05;
  }
  const double p1 = double(c1) / a.size(), p2 = double(c2) / b.size();
  const auto r = chamfer_fscore(a, b);
  CHECK(r.cd == Approx(s1 / a.size() + s2 / b.size()).epsilon(1e-12));
  CHECK(r.precision == p1);
  CHECK(r.recall == p2);
  CHECK(r.fscore == Approx(2 * p1 * p2 / (p1 + p2)).epsilon(1e-12));
  CHECK(r.fscore > 0.0);
}
