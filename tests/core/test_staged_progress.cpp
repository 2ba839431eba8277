// StagedProgress on an injected clock: the ETA is the running stage's remaining time plus the
// later stages' estimates, unknown ("?") while any estimate is; ended stages count their
// measured time only; a stage's rate runs from its first update and is known after a few
// timed intervals (before that, its estimate minus its elapsed time).
#include <catch2/catch.hpp>

#include "core/staged_progress.hpp"

using namespace sgnlf;

TEST_CASE("StagedProgress adds the later stages' estimates to the running stage's", "[core][progress]") {
  double now = 1000.0;
  StagedProgress p("job", {"a", "b", "c"}, 1e9, [&now] { return now; });
  CHECK(p.eta_s() < 0);  // nothing known
  p.estimate(0, 10.0);
  p.estimate(1, 20.0);
  CHECK(p.eta_s() < 0);  // c unknown
  p.estimate(2, 5.0);
  CHECK(p.eta_s() == 35.0);
  p.begin(0);
  now += 4.0;
  CHECK(p.eta_s() == 31.0);  // no rate yet: the estimate minus the elapsed
  CHECK(p.stage_eta_s() == 6.0);
  now += 10.0;
  CHECK(p.stage_eta_s() == 0.0);  // over its estimate: never below 0
  p.end();
  CHECK(p.eta_s() == 25.0);
  CHECK(p.current() == -1);
  CHECK(p.stage_eta_s() < 0);

  // b: 1 s before its first update (a geometric stage, a resumed run's earlier steps), then
  // 1 s per unit. The rate runs from the first update; b's own estimate (20 s) counts until
  // three intervals are timed.
  p.begin(1);
  now += 100.0;
  p.update(1, 101, "first");
  CHECK(p.eta_s() == 5.0);  // b's estimate is spent (100 s > 20 s): 0, plus c's 5 s
  for (long d = 2; d <= 3; ++d) {
    now += 1.0;
    p.update(d, 101);
  }
  CHECK(p.stage_eta_s() == 0.0);  // still no rate after two intervals
  now += 1.0;
  p.update(4, 101);
  CHECK(p.stage_eta_s() == Approx(97.0));  // 97 units at 1 s (the 100 s before unit 1 not in it)
  CHECK(p.eta_s() == Approx(102.0));
  CHECK(p.line().find("[2/3 b 4/101, 1m37s left] elapsed 1m57s ETA 1m42s") != std::string::npos);
  // Beginning a later stage ends the skipped ones with no time.
  p.begin(2);
  CHECK(p.eta_s() == 5.0);
  CHECK(p.line().find("[3/3 c, 0m05s left]") != std::string::npos);
  p.estimate(2, -1.0);
  CHECK(p.eta_s() < 0);
  CHECK(p.line().find("ETA ?") != std::string::npos);
  CHECK(p.line().find("left") == std::string::npos);
}

TEST_CASE("StagedProgress: a stage without an estimate shows its own ETA once its rate is known", "[core][progress]") {
  double now = 0.0;
  StagedProgress p("job", {"align", "train"}, 1e9, [&now] { return now; });
  p.begin(0);
  now += 30.0;          // clouds and k-d trees before the first optimiser call
  p.update(0, 100);     // the optimiser starts
  for (long d = 10; d <= 30; d += 10) {
    CHECK(p.stage_eta_s() < 0);
    CHECK(p.line().find("[1/2 align " + std::to_string(d - 10) + "/100] elapsed") != std::string::npos);
    now += 5.0;
    p.update(d, 100);
  }
  CHECK(p.stage_eta_s() == Approx(35.0));  // 70 steps at 0.5 s
  CHECK(p.stage_units_per_s() == Approx(2.0));
  CHECK(p.eta_s() < 0);                    // the training has no estimate yet
  CHECK(p.line().find("[1/2 align 30/100, 0m35s left] elapsed 0m45s ETA ?") != std::string::npos);
}
