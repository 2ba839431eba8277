// Progress reporting on stderr: a single rewritten line on a terminal, plain periodic lines
// otherwise (CI logs, pipes). Shows rate, ETA and caller-provided fields such as the loss.
// The rate and ETA are a RateEstimate (rate_estimate.hpp) over this process's updates: none
// until a few intervals are timed, measured over the later half of them. Time is read from
// `clock` (tests pass a fake one).
#pragma once
#include <string>

#include "core/clock.hpp"
#include "core/rate_estimate.hpp"

namespace sgnlf {

class Progress {
 public:
  // Steps `first` (a resumed run's step, else 0) to `total` of `label`; plain-mode lines at
  // most every `plain_every_s` seconds. The rate counts only the steps this process ran.
  Progress(std::string label, long total, double plain_every_s = 10.0, long first = 0,
           SecondsClock clock = steady_seconds());
  ~Progress();
  // Reports that `done` steps are complete; `extra` is appended (e.g. "loss 0.0123").
  void update(long done, const std::string& extra = "");
  void finish(const std::string& extra = "");
  // Restarts the rate at `done` steps: work before it (a geometric stage) is not the steps'
  // time.
  void restart_clock(long done);
  double elapsed_s() const;
  // Seconds to `total` by the rate so far; < 0 while the rate is not known.
  double eta_s() const { return rate_.remaining_s(total_); }
  // The line update() prints now (without `extra`).
  std::string line() const;

  // The line's text: `rate` steps per second (0: not known), `eta_s` < 0: not known.
  static std::string line(const std::string& label, long done, long total, double rate, double eta_s);

 private:
  std::string label_;
  long total_, first_, done_;
  double plain_every_s_;
  SecondsClock clock_;
  bool tty_;
  bool finished_ = false;
  double start_;
  RateEstimate rate_;
  double last_print_ = -1e9;
};

std::string format_duration(double seconds);

}  // namespace sgnlf
