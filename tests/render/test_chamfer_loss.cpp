// Chamfer losses (render/chamfer_loss.hpp, scene_flow_loss.hpp): values against a brute-force
// reference, gradients against central differences of the loss (points away from match
// changes), missing frames and bad shapes. Host code only.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "render/chamfer_loss.hpp"
#include "render/scene_flow_loss.hpp"

using namespace sgnlf;
using render::Point3f;

namespace {
std::vector<Point3f> cloud(size_t n, float lo, float hi, uint64_t seed) {
  Rng r(seed);
  std::vector<Point3f> p(n);
  for (auto& q : p) {
    const float a = r.uniform(lo, hi), b = r.uniform(lo, hi), c = r.uniform(lo, hi);
    q = Point3f(a, b, c);
  }
  return p;
}
// Brute force: 0.5·(mean or sum of both directions' squared NN distances), in double.
double brute(const std::vector<Point3f>& a, const std::vector<Point3f>& b, bool mean) {
  auto dir = [&](const std::vector<Point3f>& p, const std::vector<Point3f>& q) {
    double s = 0;
    for (const auto& x : p) {
      double best = std::numeric_limits<double>::max();
      for (const auto& y : q) best = std::min(best, double((x - y).squaredNorm()));
      s += best;
    }
    return mean ? s / double(p.size()) : s;
  };
  return 0.5 * (dir(a, b) + dir(b, a));
}
}  // namespace

TEST_CASE("chamfer loss equals the brute-force value; its gradient the central differences",
          "[render][chamfer]") {
  const auto pred = cloud(150, -1.0f, 1.0f, 1), target = cloud(170, -1.0f, 1.0f, 2);
  for (auto reduce : {render::ChamferReduce::Mean, render::ChamferReduce::Sum}) {
    const bool mean = reduce == render::ChamferReduce::Mean;
    const auto c = render::chamfer_loss(pred, target, reduce);
    CHECK(c.loss == Approx(brute(pred, target, mean)).epsilon(1e-6));
    const double h = 1e-4;
    int checked = 0;
    for (size_t i = 0; i < pred.size(); i += 7)
      for (int k = 0; k < 3; ++k) {
        auto p = pred, m = pred;
        p[i][k] += float(h);
        m[i][k] -= float(h);
        const double fd = (brute(p, target, mean) - brute(m, target, mean)) / (2 * h);
        CHECK(fd == Approx(c.d_pred[i][k]).margin(2e-3 * (mean ? 1.0 / 150 : 1.0)).epsilon(2e-2));
        ++checked;
      }
    CHECK(checked > 60);
  }
  const auto empty = render::chamfer_loss(pred, {}, render::ChamferReduce::Sum);
  CHECK(empty.loss == 0.0);
  CHECK(empty.d_pred.size() == pred.size());
}

TEST_CASE("ray chamfer loss: endpoints along the rays, gradient per depth", "[render][chamfer]") {
  Rng r(5);
  const size_t n = 120;
  std::vector<float> dir(3 * n), depth(n), gt(n);
  for (size_t i = 0; i < n; ++i) {
    Point3f d;
    d.x() = r.uniform(-1.f, 1.f);  // one draw per statement (core/rng.hpp)
    d.y() = r.uniform(-1.f, 1.f);
    d.z() = r.uniform(-0.2f, 0.2f);
    d.normalize();
    for (int k = 0; k < 3; ++k) dir[3 * i + k] = d[k];
    gt[i] = i % 9 == 0 ? 0.0f : r.uniform(5.f, 40.f);  // some rays without a return
    depth[i] = gt[i] + r.uniform(-2.f, 2.f);
  }
  const float scale = 0.02f;
  const auto c = render::ray_chamfer_loss(dir, depth, gt, scale, 2.0f);
  auto value = [&](const std::vector<float>& dp) {
    std::vector<Point3f> a(n), b(n);
    for (size_t i = 0; i < n; ++i) {
      const Point3f d(dir[3 * i], dir[3 * i + 1], dir[3 * i + 2]);
      a[i] = d * (dp[i] / scale);
      b[i] = d * (gt[i] / scale);
    }
    return 2.0 * brute(a, b, true);
  };
  CHECK(c.loss == Approx(value(depth)).epsilon(1e-6));
  CHECK(c.loss > 0.0);
  for (size_t i = 0; i < n; i += 5) {
    auto p = depth, m = depth;
    p[i] += 1e-3f;
    m[i] -= 1e-3f;
    CHECK((value(p) - value(m)) / 2e-3 == Approx(c.d_depth[i]).epsilon(2e-2).margin(1e-3));
  }
  CHECK_THROWS_AS(render::ray_chamfer_loss(dir, depth, gt, 0.0f), Error);
  CHECK_THROWS_AS(render::ray_chamfer_loss({1.f}, depth, gt, scale), Error);
}

TEST_CASE("scene flow loss: forward and backward steps, missing frames, ground penalty",
          "[render][chamfer]") {
  const auto pts = cloud(80, -1.0f, 1.0f, 7);
  std::vector<Point3f> next1 = pts, next2 = pts, prev1 = pts;
  const Point3f v(0.03f, -0.01f, 0.02f);
  for (size_t i = 0; i < pts.size(); ++i) {
    next1[i] += v;
    next2[i] += 2 * v;
    prev1[i] -= v;
  }
  render::FlowNeighbours nb;
  nb.next[0] = &next1;
  nb.next[1] = &next2;
  nb.prev[0] = &prev1;  // k − 2 does not exist
  std::vector<float> exact(6 * pts.size()), zero(6 * pts.size(), 0.0f);
  for (size_t i = 0; i < pts.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      exact[6 * i + k] = v[k];
      exact[6 * i + 3 + k] = -v[k];
    }
  CHECK(render::scene_flow_loss(pts, exact, nb).loss == Approx(0.0).margin(1e-10));
  const auto z = render::scene_flow_loss(pts, zero, nb);
  CHECK(z.loss > 0.01);
  // The value is the three Chamfer sums; the gradient their central differences.
  auto moved = [&](const std::vector<float>& f, int side, float s) {
    std::vector<Point3f> m(pts.size());
    for (size_t i = 0; i < pts.size(); ++i)
      for (int k = 0; k < 3; ++k) m[i][k] = pts[i][k] + s * f[6 * i + 3 * side + k];
    return m;
  };
  auto value = [&](const std::vector<float>& f) {
    return brute(moved(f, 0, 1), next1, false) + brute(moved(f, 0, 2), next2, false) +
           brute(moved(f, 1, 1), prev1, false);
  };
  Rng r(8);
  std::vector<float> f(6 * pts.size());
  for (auto& x : f) x = r.uniform(-0.03f, 0.03f);
  const auto c = render::scene_flow_loss(pts, f, nb);
  CHECK(c.loss == Approx(value(f)).epsilon(1e-6));
  for (size_t k = 0; k < f.size(); k += 11) {
    auto p = f, m = f;
    p[k] += 1e-4f;
    m[k] -= 1e-4f;
    CHECK((value(p) - value(m)) / 2e-4 == Approx(c.d_flow[k]).epsilon(2e-2).margin(2e-3));
  }
  // One step only: the k + 2 frame no longer counts.
  CHECK(render::scene_flow_loss(pts, f, nb, 1).loss ==
        Approx(brute(moved(f, 0, 1), next1, false) + brute(moved(f, 1, 1), prev1, false)));
  CHECK_THROWS_AS(render::scene_flow_loss(pts, std::vector<float>(5), nb), Error);
  const auto g = render::ground_flow_penalty({0.5f, -0.25f, 0.0f}, 0.001f);
  CHECK(g.loss == Approx(0.00075));
  CHECK(g.d_flow == std::vector<float>{0.001f, -0.001f, 0.0f});
}
