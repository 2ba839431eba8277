// The remaining time of a count of units (training steps, scans, optimiser steps) from the times
// of its progress updates, as the progress lines show it (Progress, StagedProgress).
//
// The rate runs from the first update on, not from the start: what comes before the first unit
// is done (a training's geometric stage, the first step's kernel compilation, a resumed run's
// earlier steps) is not the pace of the units. There is no estimate until `min_intervals`
// intervals after that first update have been timed (one step's time said a training of
// 4 000 steps would take 7 h), and the rate is measured over the later half of the updates so
// far, so that a slow start is forgotten while periodic costs (a pose graph rebuilt every few
// epochs) stay averaged in.
#pragma once
#include <vector>

namespace sgnlf {

class RateEstimate {
 public:
  explicit RateEstimate(int min_intervals = 3);

  // Forgets every update (a new stage).
  void reset();
  // An update at time `t_s` (seconds, any monotonic origin) with `done` units complete. An
  // update that completes no new unit is ignored (it adds no timing).
  void add(double t_s, long done);

  // True once min_intervals intervals are timed.
  bool known() const;
  // Seconds per unit over the later half of the updates; < 0 while not known().
  double seconds_per_unit() const;
  // Units per second (0 while not known()).
  double units_per_s() const;
  // Seconds until `total` units are done as of the last update: the units left at the measured
  // pace; < 0 while not known().
  double remaining_s(long total) const;

  long first_done() const { return samples_.empty() ? 0 : samples_.front().done; }
  long last_done() const { return samples_.empty() ? 0 : samples_.back().done; }

 private:
  struct Sample {
    double t;
    long done;
  };
  int min_intervals_;
  std::vector<Sample> samples_;
};

}  // namespace sgnlf
