// Robust Chamfer direction term and pose-graph loss: nearest neighbours against brute force,
// softmax weights, and analytic gradients w.r.t. (ω, u) of BOTH frames of an edge against
// central differences (symmetric relative error; a sign error gives ≈ 1).
#include <catch2/catch.hpp>

#include <limits>
#include <memory>

#include "posegraph/graph_loss.hpp"
#include "posegraph/pose_adam.hpp"
#include "gradient_fixture.hpp"
#include "smooth_scene.hpp"

using namespace sgnlf;
using namespace sgnlf::posegraph;
using namespace sgnlf::test;

TEST_CASE("match_direction equals a brute-force nearest neighbour", "[posegraph]") {
  const auto world = test::smooth_world_points(2500, 5);
  const auto src = test::cloud_seen_from(test::smooth_world_points(700, 6), kBase0);
  const auto dst = test::cloud_seen_from(world, kBase1);
  const Pose T_ds = kBase1.inverse() * kBase0;
  const auto matches = match_direction(src, dst, T_ds);
  REQUIRE(matches.size() == src.size());
  std::vector<Match> brute(src.size());
  for (size_t k = 0; k < src.size(); ++k) {
    const Vec3 q = T_ds * src.points[k].cast<double>();
    const geometry::Point3f qf = q.cast<float>();
    float best = std::numeric_limits<float>::infinity();
    for (uint32_t j = 0; j < dst.size(); ++j) {
      const float d = geometry::squared_distance(qf, dst.points[j]);
      if (d < best) best = d, brute[k].dst_index = j;  // strict: ties keep the lowest index
    }
    brute[k].sq_distance = (q - dst.points[brute[k].dst_index].cast<double>()).squaredNorm();
    REQUIRE(matches[k].dst_index == brute[k].dst_index);
    REQUIRE(matches[k].sq_distance == brute[k].sq_distance);
  }
  // The loss is built on exactly these matches.
  const RobustParams p{0.3, 0.15};
  const auto t = robust_chamfer_direction(src, dst, kBase0, kBase1, p);
  const auto r = weighted_direction(src, dst, kBase0, kBase1, brute, robust_weights(brute, p));
  CHECK(t.loss == r.loss);
  CHECK(t.grad_src == r.grad_src);
  CHECK(t.grad_dst == r.grad_dst);
}

TEST_CASE("robust weights: softmax of tau / max(d, 0.15), uniform at tau = 0", "[posegraph]") {
  std::vector<Match> m(4);
  m[0].sq_distance = 0.0;   // clamped to 0.15
  m[1].sq_distance = 0.01;  // 0.1 → clamped to 0.15
  m[2].sq_distance = 0.25;  // 0.5
  m[3].sq_distance = 4.0;   // 2
  const auto w = robust_weights(m, {0.3, 0.15});
  const double e0 = std::exp(2.0), e2 = std::exp(0.6), e3 = std::exp(0.15);
  const double z = 2 * e0 + e2 + e3;
  CHECK(w[0] == Approx(e0 / z).epsilon(1e-14));
  CHECK(w[1] == w[0]);
  CHECK(w[2] == Approx(e2 / z).epsilon(1e-14));
  CHECK(w[3] == Approx(e3 / z).epsilon(1e-14));
  for (double v : robust_weights(m, {0.0, 0.15})) CHECK(v == 0.25);
}

TEST_CASE("graph loss gradient in (omega, u) of both frames matches central differences",
          "[posegraph][gradient]") {
  // τ = 0: uniform weights, so the analytic gradient is the exact gradient of the loss.
  auto clouds = std::make_shared<std::vector<FrameCloud>>();
  clouds->push_back(test::cloud_seen_from(test::smooth_world_points(600, 1), kBase0));
  clouds->push_back(test::cloud_seen_from(test::smooth_world_points(4000, 2), kBase1));
  const GraphLoss loss(clouds, {Edge{0, 1, 1.0}});
  std::vector<PoseGrad> g;
  auto f = [&](const Vec6& x0, const Vec6& x1) {
    return loss({corrected_pose(kBase0, x0), corrected_pose(kBase1, x1)}, 0.0, g);
  };
  f(kXi0, kXi1);
  const Eigen::VectorXd analytic = stack(decoupled_gradient(kBase0, kXi0, g[0]),
                                         decoupled_gradient(kBase1, kXi1, g[1]));
  const Eigen::VectorXd numeric = central_differences(f, 1e-6);
  INFO("analytic " << analytic.transpose() << "\nnumeric  " << numeric.transpose());
  CHECK(sym_rel_error(analytic, numeric) < 1e-5);
  for (int k = 0; k < 12; ++k)  // every component, not only the dominant ones
    CHECK(std::abs(analytic[k] - numeric[k]) <= 1e-4 * std::abs(numeric[k]) + 1e-6);
  CHECK(numeric.norm() > 0.1);
  // A flipped sign is far outside the tolerance.
  CHECK(sym_rel_error(-analytic, numeric) > 1.9);
}

TEST_CASE("robust term with frozen weights (tau > 0) matches central differences",
          "[posegraph][gradient]") {
  const auto src = test::cloud_seen_from(test::smooth_world_points(600, 3), kBase0);
  const auto dst = test::cloud_seen_from(test::smooth_world_points(4000, 4), kBase1);
  const Pose T0 = corrected_pose(kBase0, kXi0), T1 = corrected_pose(kBase1, kXi1);
  const auto w = robust_weights(match_direction(src, dst, T1.inverse() * T0), {0.6, 0.15});
  REQUIRE(*std::max_element(w.begin(), w.end()) > 3.0 * *std::min_element(w.begin(), w.end()));
  auto f = [&](const Vec6& x0, const Vec6& x1) {
    const Pose A = corrected_pose(kBase0, x0), B = corrected_pose(kBase1, x1);
    return weighted_direction(src, dst, A, B, match_direction(src, dst, B.inverse() * A), w).loss;
  };
  const auto t =
      weighted_direction(src, dst, T0, T1, match_direction(src, dst, T1.inverse() * T0), w);
  const Eigen::VectorXd analytic = stack(decoupled_gradient(kBase0, kXi0, t.grad_src),
                                         decoupled_gradient(kBase1, kXi1, t.grad_dst));
  const Eigen::VectorXd numeric = central_differences(f, 1e-6);
  INFO("analytic " << analytic.transpose() << "\nnumeric  " << numeric.transpose());
  CHECK(sym_rel_error(analytic, numeric) < 1e-5);
  CHECK(numeric.norm() > 0.1);
}

TEST_CASE("graph loss is bit-identical for any thread count", "[posegraph]") {
  auto clouds = std::make_shared<std::vector<FrameCloud>>();
  std::vector<Pose> T;
  for (int k = 0; k < 5; ++k) {
    T.push_back(exp_se3((Vec6() << 0.01 * k, 0, 0.1 * k, 1.5 * k, 0.2 * k, 0).finished()));
    clouds->push_back(test::cloud_seen_from(test::smooth_world_points(800, 10 + k), T.back()));
    T.back() = corrected_pose(T.back(), (Vec6() << 0.01, -0.02, 0.03, 0.2, -0.1, 0.3).finished());
  }
  std::vector<PoseGrad> g1, g2;
  const double l1 = GraphLoss(clouds, sequential_edges(5), 0.15, 1)(T, 0.3, g1);
  const double l2 = GraphLoss(clouds, sequential_edges(5), 0.15, 2)(T, 0.3, g2);
  CHECK(l1 == l2);
  CHECK(g1 == g2);
}

TEST_CASE("trimmed robust weights: points beyond max_distance weigh 0", "[posegraph]") {
  std::vector<Match> m(4);
  m[0].sq_distance = 0.0;
  m[1].sq_distance = 0.25;  // 0.5
  m[2].sq_distance = 1.0;   // 1.0: on the limit, kept
  m[3].sq_distance = 4.0;   // 2.0: dropped
  const auto w = robust_weights(m, {0.3, 0.15, 1.0});
  const double e0 = std::exp(2.0), e1 = std::exp(0.6), e2 = std::exp(0.3);
  const double z = e0 + e1 + e2;
  CHECK(w[0] == Approx(e0 / z).epsilon(1e-14));
  CHECK(w[1] == Approx(e1 / z).epsilon(1e-14));
  CHECK(w[2] == Approx(e2 / z).epsilon(1e-14));
  CHECK(w[3] == 0.0);
  // Off (0) is the untrimmed softmax; nothing within reach gives all zeros, not NaN.
  CHECK(robust_weights(m, {0.3, 0.15, 0.0}) == robust_weights(m, {0.3, 0.15}));
  std::vector<Match> far(2);
  far[0].sq_distance = 4.0;
  far[1].sq_distance = 9.0;
  for (double v : robust_weights(far, {0.3, 0.15, 1.0})) CHECK(v == 0.0);
  CHECK_THROWS_AS(robust_weights(m, {0.3, 0.15, -1.0}), Error);
}

TEST_CASE("trimmed graph loss ignores the part of a frame the other does not see",
          "[posegraph]") {
  // Frame 1 sees the shared surfaces plus a far block that frame 0 lacks (a non-adjacent pair
  // overlaps in part). Untrimmed, the block's points pull frame 1 towards frame 0's points; at
  // 1 m the loss and gradient are those of the shared surfaces alone.
  const auto world = smooth_world_points(3000, 5);
  std::vector<Vec3> with_block = world;
  for (int k = 0; k < 600; ++k)
    with_block.push_back(Vec3(30.0 + 0.01 * (k % 30), -20.0 + 0.1 * (k / 30), 0.5 * (k % 7)));
  auto shared = std::make_shared<std::vector<FrameCloud>>();
  shared->push_back(cloud_seen_from(world, kBase0));
  shared->push_back(cloud_seen_from(world, kBase1));
  auto partial = std::make_shared<std::vector<FrameCloud>>();
  partial->push_back(cloud_seen_from(world, kBase0));
  partial->push_back(cloud_seen_from(with_block, kBase1));
  const std::vector<Pose> T = {corrected_pose(kBase0, kXi0), corrected_pose(kBase1, kXi1)};
  std::vector<PoseGrad> g_ref, g_trim, g_plain;
  const double tau = 0.5;
  const double ref = GraphLoss(shared, {Edge{0, 1, 1.0}}, 0.15, 1, robust_chamfer_direction, 1.0)(
      T, tau, g_ref);
  const double trim = GraphLoss(partial, {Edge{0, 1, 1.0}}, 0.15, 1, robust_chamfer_direction,
                                1.0)(T, tau, g_trim);
  const double plain = GraphLoss(partial, {Edge{0, 1, 1.0}})(T, tau, g_plain);
  CHECK(trim == Approx(ref).epsilon(1e-12));
  CHECK((g_trim[1] - g_ref[1]).norm() <= 1e-9 * (1.0 + g_ref[1].norm()));
  CHECK(plain > 10.0 * ref);  // the block's points dominate the untrimmed loss
  CHECK_THROWS_AS(GraphLoss(partial, {Edge{0, 1, 1.0}}, 0.15, 1, robust_chamfer_direction, -1.0),
                  Error);
}
