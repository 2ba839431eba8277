// SSIM (scikit-image default, see runtime/metrics/ssim.hpp): identities, cases computed by
// hand, and a direct per-window reference on random images.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "metrics/ssim.hpp"

using namespace sgnlf;
using namespace sgnlf::metrics;

namespace {

// Reference straight from the definition: for every pixel at ≥ 3 from the border, the 7×7
// window's means, sample variances and covariance (divisor 48), then the SSIM formula.
double ssim_reference(const std::vector<double>& x, const std::vector<double>& y, int h, int w,
                      double R) {
  const double c1 = (0.01 * R) * (0.01 * R), c2 = (0.03 * R) * (0.03 * R);
  double sum = 0;
  int count = 0;
  for (int r = 3; r < h - 3; ++r)
    for (int c = 3; c < w - 3; ++c) {
      double mx = 0, my = 0;
      for (int i = -3; i <= 3; ++i)
        for (int j = -3; j <= 3; ++j) {
          mx += x[(r + i) * w + c + j];
          my += y[(r + i) * w + c + j];
        }
      mx /= 49;
      my /= 49;
      double vx = 0, vy = 0, vxy = 0;
      for (int i = -3; i <= 3; ++i)
        for (int j = -3; j <= 3; ++j) {
          const double dx = x[(r + i) * w + c + j] - mx, dy = y[(r + i) * w + c + j] - my;
          vx += dx * dx;
          vy += dy * dy;
          vxy += dx * dy;
        }
      vx /= 48;
      vy /= 48;
      vxy /= 48;
      sum += (2 * mx * my + c1) * (2 * vxy + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2));
      ++count;
    }
  return sum / count;
}

}  // namespace

TEST_CASE("SSIM of identical images is 1", "[metrics][ssim]") {
  Rng rng(1);
  std::vector<double> x(20 * 31);
  for (auto& v : x) v = rng.uniform(0.f, 80.f);
  CHECK(ssim(x, x, 20, 31, 80.0) == Approx(1.0).epsilon(1e-14));
}

TEST_CASE("SSIM of two constant 7x7 images", "[metrics][ssim]") {
  // One window: σ = 0 ⇒ S = (2ab + C1)/(a² + b² + C1) · C2/C2.
  const std::vector<double> a(49, 0.2), b(49, 0.5);
  const double c1 = 1e-4;
  CHECK(ssim(a, b, 7, 7, 1.0) == Approx((2 * 0.2 * 0.5 + c1) / (0.04 + 0.25 + c1)));
}

TEST_CASE("SSIM of one bright pixel against black (by hand)", "[metrics][ssim]") {
  // x = δ at the centre of a 7×7 image, y = 0, R = 1: μx = 1/49, σx² = 49/48·(1/49 − 1/49²)
  // = 1/49, μy = σy² = σxy = 0 ⇒ S = C1·C2 / ((1/49² + C1)(1/49 + C2)) = 0.0081777145...
  std::vector<double> x(49, 0.0), y(49, 0.0);
  x[3 * 7 + 3] = 1.0;
  CHECK(ssim(x, y, 7, 7, 1.0) == Approx(0.008177714534840484).epsilon(1e-12));
}

TEST_CASE("SSIM under a constant offset (by hand)", "[metrics][ssim]") {
  // x(r, c) = c on a 7×9 image, y = x + 0.5, R = 1. Cropped pixels: row 3, columns 3, 4, 5,
  // where μx = c and σx² = σy² = σxy, so S(c) = (2c(c + 0.5) + C1)/(c² + (c + 0.5)² + C1).
  std::vector<double> x(63), y(63);
  for (int r = 0; r < 7; ++r)
    for (int c = 0; c < 9; ++c) {
      x[r * 9 + c] = c;
      y[r * 9 + c] = c + 0.5;
    }
  CHECK(ssim(x, y, 7, 9, 1.0) == Approx(0.9922713126978286).epsilon(1e-12));
}

TEST_CASE("SSIM equals the per-window definition on random images", "[metrics][ssim]") {
  Rng rng(2);
  const int h = 16, w = 23;
  std::vector<double> x(h * w), y(h * w);
  for (int i = 0; i < h * w; ++i) {
    x[i] = rng.uniform(0.f, 30.f);
    y[i] = x[i] + rng.uniform(-5.f, 5.f);
  }
  const double s = ssim(x, y, h, w, 30.0);
  CHECK(s == Approx(ssim_reference(x, y, h, w, 30.0)).epsilon(1e-10));
  CHECK(s < 0.99);
  CHECK(ssim(x, y, h, w, 30.0) == Approx(ssim(y, x, h, w, 30.0)).epsilon(1e-14));
}

TEST_CASE("SSIM rejects bad shapes, ranges and values", "[metrics][ssim]") {
  const std::vector<double> a(49, 1.0), b(48, 1.0);
  CHECK_THROWS_AS(ssim(a, b, 7, 7, 1.0), Error);
  CHECK_THROWS_AS(ssim(a, a, 7, 7, 0.0), Error);
  CHECK_THROWS_AS(ssim(std::vector<double>(36, 1.0), std::vector<double>(36, 1.0), 6, 6, 1.0),
                  Error);
  std::vector<double> c = a;
  c[5] = std::nan("");
  CHECK_THROWS_AS(ssim(a, c, 7, 7, 1.0), Error);
}
