// Cross-frame reprojection, backward: dL/dd_p, dL/dξ_i and dL/dξ_j of L = Σ_t w_t·D_ij[t]
// (ξ = (ω, u) of T = T_init·[Exp(ω)|u], PoseSet's parametrisation) from the double reference
// and from the device, against central differences of the double reference at a non-zero ξ
// (pixels whose winner changes under the step are left out of both sides: the pixel choice is
// not differentiated); and run-to-run determinism of the gradients.
#include <catch2/catch.hpp>

#include <cstring>

#include "core/rng.hpp"
#include "reproject_reference.hpp"
#include "reproject_test_data.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {
struct Problem {
  Sensor s;
  std::vector<float> depth_f;
  std::vector<double> depth, w;
  Pose T_init_i, T_init_j;
  Vec6 xi_i, xi_j;

  Pose T_lidarj_lidari(const Vec6& xi, const Vec6& xj) const {
    return corrected_pose(T_init_j, xj).inverse(Eigen::Isometry) * corrected_pose(T_init_i, xi);
  }
};

// Two simulated frames (66 × 256), with initial poses chosen so that the corrections ξ (rotations
// of 0.2–0.4 rad) give back the true poses; w uniform in [−1, 1] per target pixel.
const Problem& problem() {
  static const Problem P = [] {
    const Dataset& d = test::reproj_pair("kitti360-low-a", 256);
    Problem p;
    p.s = d.sensor;
    p.depth_f = d.frames[0].image.range;
    p.depth.assign(p.depth_f.begin(), p.depth_f.end());
    p.xi_i << 0.3, -0.2, 0.25, 0.4, -0.3, 0.2;
    p.xi_j << -0.15, 0.35, -0.1, -0.2, 0.5, 0.1;
    p.T_init_i = d.frames[0].T_world_lidar * exp_se3_decoupled(p.xi_i).inverse(Eigen::Isometry);
    p.T_init_j = d.frames[1].T_world_lidar * exp_se3_decoupled(p.xi_j).inverse(Eigen::Isometry);
    Rng rng(3, 5);
    p.w.resize(size_t(p.s.height) * p.s.width);
    for (auto& v : p.w) v = 2.0 * rng.uniform_double() - 1.0;
    return p;
  }();
  return P;
}

// Pose gradients of the reference for weights w (double), through `winner`.
std::pair<Vec6, Vec6> ref_pose_grad(const Problem& P, const test::RefReprojGeometry<double>& g,
                                    const std::vector<int>& winner, const std::vector<double>& w) {
  const Pose T_ji = P.T_lidarj_lidari(P.xi_i, P.xi_j);
  const auto b = test::ref_reproject_backward(g, P.depth, T_ji, winner, w);
  return test::ref_reproject_xi_gradient(b, T_ji, P.xi_i, P.xi_j);
}

// The device's float sums differ from double by ~1e-9 of Σ|terms| here (random signs); 5e-8
// still catches a 0.1 % error in the smallest gradient component (~2e-4 of Σ|terms|).
constexpr double kFloatSum = 5e-8;

// Per-component scale: float sums of |w|·|dD/dξ_k| (u: |m| = 1; ω: |x × m| ≤ |x|).
Vec6 float_sum_scale(const Problem& P, const std::vector<int>& winner,
                     const std::vector<double>& w) {
  double su = 0, sw = 0;
  for (size_t t = 0; t < winner.size(); ++t) {
    if (winner[t] < 0) continue;
    su += std::abs(w[t]);
    sw += std::abs(w[t]) * P.depth[size_t(winner[t])];
  }
  Vec6 s;
  s << sw, sw, sw, su, su, su;
  return s;
}

struct DeviceGrad {
  std::vector<float> grad_depth;
  render::ReprojectionPoseGradient pose;
  std::vector<int> winner;
};

DeviceGrad device_grad(render::CrossFrameReprojection& rp, const Problem& P,
                       const std::vector<double>& w) {
  auto& rt = test::runtime();
  auto depth = cl::Buffer::from(rt, P.depth_f);
  auto out = rp.make_output();
  const auto ctx = rp.forward(depth, corrected_pose(P.T_init_i, P.xi_i),
                              corrected_pose(P.T_init_j, P.xi_j), out);
  auto grad = cl::Buffer::from(rt, std::vector<float>(w.begin(), w.end()));
  cl::Buffer grad_depth(rt, P.depth_f.size() * 4);
  DeviceGrad r;
  r.pose = rp.backward(ctx, depth, out, grad, grad_depth, P.xi_i, P.xi_j);
  r.grad_depth = grad_depth.read_vec<float>(P.depth_f.size());
  r.winner = rp.read(out).winner;
  return r;
}
}  // namespace

TEST_CASE("Reprojection pose gradients match central differences (reference and device)",
          "[render][reproject][fd]") {
  const Problem& P = problem();
  const auto g = test::ref_reproj_geometry<double>(P.s, P.s, 1.0);
  const auto base = test::ref_reproject_forward(g, P.depth, test::ref_rows<double>(P.T_lidarj_lidari(P.xi_i, P.xi_j)));
  render::CrossFrameReprojection rp(test::runtime(), P.s, P.s, 1.0);
  size_t covered = 0;
  for (int t : base.winner) covered += t >= 0;
  REQUIRE(covered > base.winner.size() / 3);
  // Pixels where the float device picks another winner than the double reference (points on a
  // pixel boundary) are left out as well.
  const auto dev_winner = device_grad(rp, P, P.w).winner;
  const double h = 1e-6;
  for (int k = 0; k < 12; ++k) {
    Vec6 xi_p = P.xi_i, xj_p = P.xi_j, xi_m = P.xi_i, xj_m = P.xi_j;
    (k < 6 ? xi_p : xj_p)[k % 6] += h;
    (k < 6 ? xi_m : xj_m)[k % 6] -= h;
    const auto fp = test::ref_reproject_forward(g, P.depth, test::ref_rows<double>(P.T_lidarj_lidari(xi_p, xj_p)));
    const auto fm = test::ref_reproject_forward(g, P.depth, test::ref_rows<double>(P.T_lidarj_lidari(xi_m, xj_m)));
    // Pixels whose winner the step changes carry a jump, not a derivative: leave them out.
    std::vector<double> w_k = P.w;
    size_t changed = 0;
    double numeric = 0;
    for (size_t t = 0; t < w_k.size(); ++t) {
      if (fp.winner[t] != base.winner[t] || fm.winner[t] != base.winner[t] ||
          dev_winner[t] != base.winner[t]) {
        w_k[t] = 0;
        ++changed;
        continue;
      }
      numeric += w_k[t] * (fp.range[t] - fm.range[t]);
    }
    numeric /= 2 * h;
    CHECK(changed <= covered / 200);
    const auto [ref_i, ref_j] = ref_pose_grad(P, g, base.winner, w_k);
    const double analytic = k < 6 ? ref_i[k] : ref_j[k - 6];
    const Vec6 scale = float_sum_scale(P, base.winner, w_k);
    const auto dev = device_grad(rp, P, w_k);
    const double device = k < 6 ? dev.pose.xi_i[k] : dev.pose.xi_j[k - 6];
    INFO((k < 6 ? "xi_i[" : "xi_j[") << k % 6 << "] numeric " << numeric << " analytic " << analytic
                                     << " device " << device << " changed " << changed);
    CHECK(std::abs(analytic - numeric) <= 1e-6 * std::abs(numeric) + 1e-9 * scale[k % 6]);
    CHECK(std::abs(device - numeric) <= kFloatSum * scale[k % 6]);
    if (k >= 6 && k < 9) {
      // Turning frame j about its own origin leaves every range in frame j unchanged.
      CHECK(analytic == 0.0);
      CHECK(std::abs(numeric) <= 1e-9 * scale[k % 6]);
    }
  }
}

TEST_CASE("Reprojection depth gradients match central differences and the reference",
          "[render][reproject][fd]") {
  const Problem& P = problem();
  const auto g = test::ref_reproj_geometry<double>(P.s, P.s, 1.0);
  const Pose T_ji = P.T_lidarj_lidari(P.xi_i, P.xi_j);
  const auto rows = test::ref_rows<double>(T_ji);
  const auto base = test::ref_reproject_forward(g, P.depth, rows);
  render::CrossFrameReprojection rp(test::runtime(), P.s, P.s, 1.0);
  const auto dev = device_grad(rp, P, P.w);
  // The device backward runs through the device's winners; the reference through the same.
  const auto ref_dev = test::ref_reproject_backward(g, P.depth, T_ji, dev.winner, P.w);
  const auto ref = test::ref_reproject_backward(g, P.depth, T_ji, base.winner, P.w);
  std::vector<float> ref_f(ref_dev.grad_depth.begin(), ref_dev.grad_depth.end());
  CHECK(test::max_sym_rel_err(dev.grad_depth, ref_f, 1e-6) <= 1e-5);
  size_t nonzero = 0;
  for (float v : dev.grad_depth) nonzero += v != 0.f;
  CHECK(nonzero > P.depth.size() / 4);
  // Central differences of D_ij at the winner's pixel for 200 winners.
  Rng rng(11, 2);
  int checked = 0;
  for (int tries = 0; tries < 2000 && checked < 200; ++tries) {
    const size_t t = rng.below(uint32_t(base.winner.size()));
    const int p = base.winner[t];
    if (p < 0) continue;
    const double h = 1e-6 * P.depth[size_t(p)];
    double qp = 0, qm = 0;
    REQUIRE(test::ref_target(g, rows, p, P.depth[size_t(p)] + h, &qp) == int(t));
    REQUIRE(test::ref_target(g, rows, p, P.depth[size_t(p)] - h, &qm) == int(t));
    const double numeric = P.w[t] * (std::sqrt(qp) - std::sqrt(qm)) / (2 * h);
    INFO("source " << p << " target " << t);
    CHECK(ref.grad_depth[size_t(p)] == Approx(numeric).epsilon(1e-6).margin(1e-9));
    CHECK(dev.grad_depth[size_t(p)] == Approx(numeric).epsilon(1e-5).margin(1e-6));
    ++checked;
  }
  CHECK(checked == 200);
  // The pose gradients of the full loss agree too.
  const auto [ref_i, ref_j] = test::ref_reproject_xi_gradient(ref_dev, T_ji, P.xi_i, P.xi_j);
  const Vec6 scale = float_sum_scale(P, dev.winner, P.w);
  for (int k = 0; k < 6; ++k) {
    INFO("component " << k);
    CHECK(std::abs(dev.pose.xi_i[k] - ref_i[k]) <= kFloatSum * scale[k]);
    CHECK(std::abs(dev.pose.xi_j[k] - ref_j[k]) <= kFloatSum * scale[k]);
  }
}

TEST_CASE("Reprojection backward is bit-identical from run to run", "[render][reproject]") {
  const Problem& P = problem();
  render::CrossFrameReprojection rp(test::runtime(), P.s, P.s, 1.0);
  const auto a = device_grad(rp, P, P.w);
  for (int run = 0; run < 3; ++run) {
    const auto b = device_grad(rp, P, P.w);
    CHECK(std::memcmp(a.grad_depth.data(), b.grad_depth.data(), a.grad_depth.size() * 4) == 0);
    CHECK(a.pose.xi_i == b.pose.xi_i);
    CHECK(a.pose.xi_j == b.pose.xi_j);
    CHECK(a.winner == b.winner);
  }
  CHECK(a.pose.xi_i.norm() > 0);
  CHECK(a.pose.xi_j.tail<3>().norm() > 0);
}
