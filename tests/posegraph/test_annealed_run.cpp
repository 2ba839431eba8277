// run_annealed's schedule: the clock (τ) per call, held at 1 on request, and the learning rates
// decaying from lr_start to lr_final, on a loss whose minimum is far away (so every Adam step
// moves a frame by about its learning rate).
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "posegraph/annealed_run.hpp"

using namespace sgnlf;
using namespace sgnlf::posegraph;

namespace {

struct Recorded {
  std::vector<double> clocks, moved;
};

Recorded run(const AnnealConfig& a) {
  GeometricConfig base;
  base.tau_scale = 0.3;
  // L = Σ_k 1000 · x_k: a constant gradient in the world x direction, no minimum in reach.
  const PoseLoss loss = [](const std::vector<Pose>& T, double, std::vector<PoseGrad>& g) {
    g.assign(T.size(), PoseGrad::Zero());
    double l = 0.0;
    for (size_t k = 0; k < T.size(); ++k) {
      l += 1000.0 * T[k].translation().x();
      g[k](3) = 1000.0;
    }
    return l;
  };
  std::vector<Pose> T(2, Pose::Identity());
  Recorded r;
  run_annealed(loss, T.size(), base, a, T, [&](int, double clock, const GeometricResult& res) {
    r.clocks.push_back(clock);
    r.moved.push_back(res.max_translation_m);
  });
  return r;
}

}  // namespace

TEST_CASE("run_annealed: clock per call and learning-rate decay from lr_start to lr_final",
          "[posegraph]") {
  AnnealConfig a;
  a.steps = 40;
  a.per_call = 10;
  a.lr_final = 0.05;
  const Recorded plain = run(a);
  REQUIRE(plain.clocks.size() == 4);
  for (int k = 0; k < 4; ++k) CHECK(plain.clocks[k] == Approx((k + 1) / 4.0));
  // Ten Adam steps on a constant gradient move a frame by 10 · lr: 10 · 0.02 · decay.
  CHECK(plain.moved[0] == Approx(10 * 0.02).epsilon(0.01));
  CHECK(plain.moved[3] / plain.moved[0] == Approx(std::pow(0.05, 3.0 / 4.0)).epsilon(0.01));

  a.lr_start = 0.25;
  a.hold_clock = true;
  const Recorded held = run(a);
  REQUIRE(held.clocks.size() == 4);
  for (double c : held.clocks) CHECK(c == 1.0);
  CHECK(held.moved[0] == Approx(10 * 0.02 * 0.25).epsilon(0.01));
  CHECK(held.moved[3] / held.moved[0] ==
        Approx(std::pow(0.05 / 0.25, 3.0 / 4.0)).epsilon(0.01));

  a.lr_start = 0.0;
  CHECK_THROWS_AS(run(a), ConfigError);
}
