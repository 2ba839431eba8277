// The progress line's rate and ETA on an injected clock: a resumed run counts only the steps it
// ran; no ETA until a few intervals are timed; the restarted clock leaves out what came before.
#include <catch2/catch.hpp>

#include "core/progress.hpp"

using namespace sgnlf;

TEST_CASE("the progress line's text", "[core][progress]") {
  CHECK_THAT(Progress::line("train x", 300, 4000, 30.0, 123.0),
             Catch::Contains("300/4000 (8%) 30.00 it/s ETA 2m03s"));
  CHECK_THAT(Progress::line("train x", 3000, 4000, 0.0, -1.0), Catch::Contains("0.00 it/s ETA ?"));
  CHECK(format_duration(-1.0) == "?");
  CHECK(format_duration(7.0 * 3600 + 61) == "7h01m");
}

TEST_CASE("the progress rate counts the steps this process ran, once a few are timed", "[core][progress]") {
  double now = 100.0;
  auto clock = [&now] { return now; };
  // Resumed at step 3000 of 4000, 30 steps a second: 30 it/s, not 3300 / 10 s = 330 it/s (a
  // resumed run showed 529 it/s for a real 30).
  Progress p("train x", 4000, 1e9, 3000, clock);
  CHECK(p.eta_s() < 0);
  CHECK_THAT(p.line(), Catch::Contains("3000/4000 (75%) 0.00 it/s ETA ?"));
  for (long s = 3100; s <= 3200; s += 100) {
    now += 100.0 / 30.0;
    p.update(s);
  }
  CHECK(p.eta_s() < 0);  // two intervals after the start: not yet
  now += 100.0 / 30.0;
  p.update(3300);
  CHECK(p.eta_s() == Approx(700.0 / 30.0));
  CHECK_THAT(p.line(), Catch::Contains("3300/4000 (82%) 30.00 it/s ETA 0m23s"));
  CHECK(p.elapsed_s() == Approx(300.0 / 30.0));
}

TEST_CASE("the progress clock restarts after the work before the first step", "[core][progress]") {
  double now = 0.0;
  auto clock = [&now] { return now; };
  Progress p("train x", 1000, 1e9, 0, clock);
  now = 150.0;  // a geometric stage before step 0
  p.restart_clock(0);
  for (long s = 1; s <= 4; ++s) {
    now += 1.0;
    p.update(s);
  }
  CHECK(p.eta_s() == Approx(996.0));  // 1 s a step: the 150 s before the first step not in it
  CHECK(p.elapsed_s() == Approx(4.0));
}
