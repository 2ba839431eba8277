// StagedProgress: the ETA is the running stage's remaining time plus the later stages'
// estimates, unknown ("?") while any estimate is; ended stages count their measured time only.
#include <catch2/catch.hpp>

#include <thread>

#include "core/staged_progress.hpp"

using namespace sgnlf;

TEST_CASE("StagedProgress adds the later stages' estimates to the running stage's", "[workflow][progress]") {
  StagedProgress p("job", {"a", "b", "c"}, 1e9);
  CHECK(p.eta_s() < 0);  // nothing known
  p.estimate(0, 10.0);
  p.estimate(1, 20.0);
  CHECK(p.eta_s() < 0);  // c unknown
  p.estimate(2, 5.0);
  CHECK(p.eta_s() == Approx(35.0).margin(0.05));
  p.begin(0);
  CHECK(p.eta_s() == Approx(35.0).margin(0.5));  // no rate yet: the estimate minus the elapsed
  p.end();
  CHECK(p.eta_s() == Approx(25.0));
  // The rate runs from the stage's first update: the second before it (a geometric stage, a
  // resumed run's earlier steps) does not count. 1 → 3 of 101 units in the 0.1 s slept → 98
  // units ≈ 4.9 s, plus c's 5 s (b's own estimate, 20 s, no longer counts). Counted from the
  // stage's start (3 units in ≥ 1.1 s) it would be ≥ 36 s.
  p.begin(1);
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  p.update(1, 101, "first");
  // No rate yet: b's estimate minus its time (≥ 1 s; more when the sleep overran), plus c's.
  CHECK(p.eta_s() <= 24.0 + 1e-3);
  CHECK(p.eta_s() > 19.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  p.update(3, 101, "");
  const double eta = p.eta_s();
  CHECK(eta >= 5.0 + 4.9 - 1e-3);
  CHECK(eta < 25.0);
  CHECK(p.line().find("[2/3 b 3/101]") != std::string::npos);
  // Beginning a later stage ends the skipped ones with no time.
  p.begin(2);
  CHECK(p.eta_s() == Approx(5.0).margin(0.5));
  p.estimate(2, -1.0);
  CHECK(p.eta_s() < 0);
  CHECK(p.line().find("ETA ?") != std::string::npos);
}
