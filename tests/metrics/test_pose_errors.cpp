// Umeyama SE(3) alignment, ATE and RPE (protocol §4): rigid motions give zero, known
// perturbations give hand-computed values.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "metrics/evaluate.hpp"
#include "metrics/pose_errors.hpp"

using namespace sgnlf;
using namespace sgnlf::metrics;

namespace {

Pose pose_at(const Vec3& t, const Vec3& w = Vec3::Zero()) {
  Pose T = Pose::Identity();
  T.linear() = exp_so3(w);
  T.translation() = t;
  return T;
}

std::vector<Pose> random_trajectory(Rng& rng, int n) {
  std::vector<Pose> out;
  for (int i = 0; i < n; ++i) {
    Vec6 xi;
    for (int k = 0; k < 6; ++k) xi[k] = rng.normal() * (k < 3 ? 0.3 : 5.0);
    out.push_back(exp_se3(xi));
  }
  return out;
}

}  // namespace

TEST_CASE("Umeyama recovers a rigid transform exactly", "[metrics][pose]") {
  Rng rng(7);
  Vec6 xi;
  xi << 0.4, -0.7, 1.1, 3.0, -2.0, 5.0;
  const Pose T = exp_se3(xi);
  std::vector<Vec3> est, gt;
  for (int i = 0; i < 10; ++i) {
    est.emplace_back(rng.normal() * 4, rng.normal() * 4, rng.normal() * 4);
    gt.push_back(T * est.back());
  }
  CHECK((umeyama_se3(est, gt).matrix() - T.matrix()).norm() < 1e-10);
  CHECK_THROWS_AS(umeyama_se3(est, std::vector<Vec3>(3)), Error);
}

TEST_CASE("a rigidly moved trajectory has zero ATE and RPE", "[metrics][pose]") {
  Rng rng(9);
  const auto gt = random_trajectory(rng, 12);
  Vec6 xi;
  xi << -0.3, 0.2, 2.5, 10.0, 4.0, -1.0;
  const Pose M = exp_se3(xi);
  std::vector<Pose> est;
  for (const auto& T : gt) est.push_back(M * T);
  const PoseErrors e = compute_pose_errors(est, gt);
  CHECK(e.ate_m < 1e-9);
  CHECK(e.rpe_t_cm < 1e-7);
  CHECK(e.rpe_r_deg < 1e-5);  // arccos near 1 amplifies rounding: 1e-5° ≈ 2e-7 rad
}

TEST_CASE("ATE and RPE_t of a scaled square (by hand)", "[metrics][pose]") {
  // gt at the corners (±1, ±1, 0) in order round the square, identity rotations; est = 1.1·gt.
  // C ∝ I ⇒ R = I, centroids 0 ⇒ t = 0. Each position error 0.1·√2 ⇒ ATE = 0.1414 m.
  // Consecutive sides have length 2 ⇒ ‖trans(E)‖ = 0.1·2 = 0.2 m = 20 cm; RPE_r = 0.
  const std::vector<Vec3> corners = {Vec3(1, 1, 0), Vec3(-1, 1, 0), Vec3(-1, -1, 0),
                                     Vec3(1, -1, 0)};
  std::vector<Pose> gt, est;
  for (const auto& c : corners) {
    gt.push_back(pose_at(c));
    est.push_back(pose_at(1.1 * c));
  }
  const PoseErrors e = compute_pose_errors(est, gt);
  CHECK(e.ate_m == Approx(0.1 * std::sqrt(2.0)).epsilon(1e-12));
  CHECK(e.rpe_t_cm == Approx(20.0).epsilon(1e-12));
  CHECK(e.rpe_r_deg == Approx(0.0).margin(1e-6));
  // The errors lie in the x, y plane: the horizontal ATE is the 3D one; the square's z = 0.
  CHECK(e.ate_h_m == Approx(e.ate_m).epsilon(1e-12));
  CHECK(e.planar_reference);
  const Json j = pose_metrics(est, gt);
  CHECK(j.size() == 5);
  CHECK(j.at("ate_m").get<double>() == Approx(0.1 * std::sqrt(2.0)));
  CHECK(j.at("ate_h_m").get<double>() == Approx(0.1 * std::sqrt(2.0)));
  CHECK(j.at("ate_reference") == "horizontal");
  CHECK(j.at("rpe_t_cm").get<double>() == Approx(20.0));
}

TEST_CASE("horizontal ATE: z errors left after the 3D alignment count in ATE only (by hand)",
          "[metrics][pose][ate_h]") {
  // gt: the square's corners (±2, ±2, 0) in order; est: the same x, y, z = +0.1 at corners 0
  // and 2, −0.1 at 1 and 3. Centroids 0 ⇒ t = 0; C = 1/4 Σ p_gt (p_est)ᵀ = diag(4, 4, 0), the
  // z offsets cancel in C (Σ z_est·x_gt = Σ z_est·y_gt = 0) ⇒ R = I. The aligned estimate keeps
  // its z errors of 0.1: ATE = 0.1 m, ATE_h = 0.
  const std::vector<Vec3> corners = {Vec3(2, 2, 0), Vec3(-2, 2, 0), Vec3(-2, -2, 0),
                                     Vec3(2, -2, 0)};
  std::vector<Pose> gt, est;
  for (size_t i = 0; i < corners.size(); ++i) {
    gt.push_back(pose_at(corners[i]));
    est.push_back(pose_at(corners[i] + Vec3(0, 0, i % 2 ? -0.1 : 0.1)));
  }
  const PoseErrors e = compute_pose_errors(est, gt);
  CHECK(e.ate_m == Approx(0.1).epsilon(1e-12));
  CHECK(e.ate_h_m == Approx(0.0).margin(1e-12));
  CHECK(e.planar_reference);  // every gt z is 0
  const Json j = pose_metrics(est, gt);
  CHECK(j.at("ate_h_m").get<double>() == Approx(0.0).margin(1e-12));
  CHECK(j.at("ate_reference") == "horizontal");
  // The same alignment as the 3D ATE, not a 2D one: a rigid move of the estimate (here a tilt
  // about x, which a 2D fit could not undo) changes neither value.
  Vec6 xi;
  xi << 0.3, -0.2, 0.5, 4.0, 1.0, -3.0;
  std::vector<Pose> moved;
  for (const auto& T : est) moved.push_back(exp_se3(xi) * T);
  const PoseErrors m = compute_pose_errors(moved, gt);
  CHECK(m.ate_m == Approx(0.1).epsilon(1e-9));
  CHECK(m.ate_h_m == Approx(0.0).margin(1e-9));
  // Swapped: a z-planar estimate against the zig-zag reference. The reference is not planar
  // (its z spread is 0.2 m) ⇒ "3d"; the errors are the same.
  const PoseErrors s = compute_pose_errors(gt, est);
  CHECK_FALSE(s.planar_reference);
  CHECK(s.ate_m == Approx(0.1).epsilon(1e-12));
  CHECK(s.ate_h_m == Approx(0.0).margin(1e-12));
  CHECK(pose_metrics(gt, est).at("ate_reference") == "3d");
}

TEST_CASE("a reference is planar when every z is equal within 1e-6 m", "[metrics][pose][ate_h]") {
  std::vector<Pose> poses;
  for (int i = 0; i < 5; ++i) poses.push_back(pose_at(Vec3(3.0 * i, 0.2 * i * i, 1.5)));
  CHECK(is_planar(poses));  // z = 1.5 everywhere: planar at any height
  poses[3].translation().z() += 0.9e-6;
  CHECK(is_planar(poses));
  poses[1].translation().z() -= 0.2e-6;  // spread 1.1e-6 m
  CHECK_FALSE(is_planar(poses));
  CHECK_FALSE(is_planar({}));
}

TEST_CASE("RPE of one rotated frame (by hand)", "[metrics][pose]") {
  // gt: identity rotations at p_i = (2i, i²/2, 0), i = 0..4. est: the same, but frame 2 rotated
  // by θ about z. Positions agree ⇒ ATE = 0. Pair (1,2): E = [Rz(−θ) | 0]; pair (2,3):
  // E = [Rz(θ) | (Rz(θ) − I)·Δp], Δp = p3 − p2 = (2, 2.5, 0), ‖·‖ = 2·sin(θ/2)·‖Δp‖.
  // RPE_r = 2θ/4, RPE_t = 100·2·sin(θ/2)·‖Δp‖/4 cm.
  const double theta = 0.2;
  std::vector<Pose> gt, est;
  for (int i = 0; i < 5; ++i) {
    const Vec3 p(2.0 * i, 0.5 * i * i, 0.0);
    gt.push_back(pose_at(p));
    est.push_back(pose_at(p, i == 2 ? Vec3(0, 0, theta) : Vec3::Zero()));
  }
  const PoseErrors e = compute_pose_errors(est, gt);
  CHECK(e.ate_m == Approx(0.0).margin(1e-12));
  CHECK(e.rpe_r_deg == Approx(2.0 * theta / 4.0 * 180.0 / M_PI).epsilon(1e-12));
  CHECK(e.rpe_t_cm ==
        Approx(100.0 * 2.0 * std::sin(theta / 2.0) * std::hypot(2.0, 2.5) / 4.0).epsilon(1e-12));
  // A rigid move of the estimate does not change any value.
  Vec6 xi;
  xi << 0.5, 0.1, -0.4, 7.0, -3.0, 2.0;
  for (auto& T : est) T = exp_se3(xi) * T;
  const PoseErrors e2 = compute_pose_errors(est, gt);
  CHECK(e2.ate_m == Approx(0.0).margin(1e-9));
  // arccos near 1 turns ~1e-16 of rounding in tr(R) into ~1e-8 rad per pair: margin 1e-5°.
  CHECK(e2.rpe_r_deg == Approx(e.rpe_r_deg).margin(1e-5));
  CHECK(e2.rpe_t_cm == Approx(e.rpe_t_cm).epsilon(1e-9));
}

TEST_CASE("pose metrics reject mismatched, short or non-finite input", "[metrics][pose]") {
  const std::vector<Pose> two(2, Pose::Identity()), three(3, Pose::Identity());
  CHECK_THROWS_AS(compute_pose_errors(two, three), Error);
  CHECK_THROWS_AS(compute_pose_errors({Pose::Identity()}, {Pose::Identity()}), Error);
  auto bad = two;
  bad[1].translation().x() = std::nan("");
  CHECK_THROWS_AS(compute_pose_errors(bad, two), Error);
}
