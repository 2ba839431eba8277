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
  // A rate: 2 of 4 units in the time slept (≥ 0.1 s) → as long again, plus c's 5 s; b's own
  // estimate (20 s) no longer counts.
  p.begin(1);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  p.update(2, 4, "half");
  CHECK(p.eta_s() >= 5.1 - 1e-3);
  CHECK(p.eta_s() < 10.0);
  CHECK(p.line().find("[2/3 b 2/4]") != std::string::npos);
  // A resumed stage: units done before this process (first) do not count in the rate.
  p.update(3, 4, "", 2);
  CHECK(p.eta_s() > 5.0);
  // Beginning a later stage ends the skipped ones with no time.
  p.begin(2);
  CHECK(p.eta_s() == Approx(5.0).margin(0.5));
  p.estimate(2, -1.0);
  CHECK(p.eta_s() < 0);
  CHECK(p.line().find("ETA ?") != std::string::npos);
}
