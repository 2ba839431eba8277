// RateEstimate: no estimate until min_intervals intervals after the first update are timed;
// the pace over the later half of the updates (a slow start forgotten, periodic costs kept).
#include <catch2/catch.hpp>

#include "core/rate_estimate.hpp"

using namespace sgnlf;

TEST_CASE("RateEstimate waits for a few timed intervals", "[core][progress]") {
  RateEstimate r(3);
  CHECK_FALSE(r.known());
  CHECK(r.remaining_s(100) < 0);
  CHECK(r.units_per_s() == 0.0);
  r.add(10.0, 1);  // the first update: the time before it is not the units' pace
  r.add(11.0, 2);
  r.add(12.0, 3);
  CHECK_FALSE(r.known());  // two intervals
  r.add(13.0, 3);          // no new unit: no timing
  CHECK_FALSE(r.known());
  r.add(13.0, 4);
  REQUIRE(r.known());
  // Samples 1, 2, 3, 4 at 10-13 s: the later half runs from sample (4 - 1) / 2 = 1 (2 units, 2 s).
  CHECK(r.seconds_per_unit() == Approx(1.0));
  CHECK(r.units_per_s() == Approx(1.0));
  CHECK(r.remaining_s(100) == Approx(96.0));
  CHECK(r.remaining_s(2) == 0.0);  // past the total
  r.reset();
  CHECK_FALSE(r.known());
  CHECK_THROWS(RateEstimate(0));
}

TEST_CASE("RateEstimate forgets a slow first step and keeps periodic costs", "[core][progress]") {
  // A training logged every 25 steps at 0.2 s a step whose first logged interval also compiled
  // kernels for 150 s: the whole-run rate from step 1 would say 3 975 × 6.2 s ≈ 7 h at step 25.
  RateEstimate r(3);
  double t = 0.0;
  r.add(t, 1);
  t += 150.0 + 24 * 0.2;
  r.add(t, 25);
  for (long s = 50; s <= 200; s += 25) {
    t += 25 * 0.2;
    r.add(t, s);
  }
  // Updates at 1, 25, ..., 200 (9): the later half from the 5th (step 100): 100 steps in 20 s.
  CHECK(r.seconds_per_unit() == Approx(0.2));
  CHECK(r.remaining_s(4000) == Approx(3800 * 0.2));
  // A pause every 4th interval (a pose graph rebuilt every few epochs) stays in the average.
  RateEstimate p(3);
  t = 0.0;
  p.add(t, 0);
  for (long k = 1; k <= 16; ++k) {
    t += 10.0 + (k % 4 == 0 ? 20.0 : 0.0);
    p.add(t, 10 * k);
  }
  // Later half: samples 8 … 16 (80 units): 80 s of steps and two 20 s pauses.
  CHECK(p.seconds_per_unit() == Approx(120.0 / 80.0));
}
