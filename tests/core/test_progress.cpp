// The progress line's rate and ETA: a resumed run counts only the steps it ran.
#include <catch2/catch.hpp>

#include "core/progress.hpp"

using namespace sgnlf;

TEST_CASE("the progress rate counts the steps this process ran", "[core][progress]") {
  // Fresh: 300 steps in 10 s of 4000.
  CHECK_THAT(Progress::line("train x", 0, 300, 4000, 10.0),
             Catch::Contains("300/4000 (8%) 30.00 it/s ETA 2m03s"));
  // Resumed at step 3000, 300 steps in 10 s: 30 it/s, not 3300 / 10 s = 330 it/s (a
  // resumed run showed 529 it/s for a real 30).
  CHECK_THAT(Progress::line("train x", 3000, 3300, 4000, 10.0),
             Catch::Contains("3300/4000 (82%) 30.00 it/s ETA 0m23s"));
  // No step yet: no rate, no ETA.
  CHECK_THAT(Progress::line("train x", 3000, 3000, 4000, 5.0), Catch::Contains("0.00 it/s ETA ?"));
}
