// One progress line over a job of several stages of unequal cost (sgnlf reconstruct: odometry,
// the coarse geometric alignment, training, evaluation, renders, ...). Each stage carries an
// estimate of its duration that the caller refines as it learns the real cost; the line shows
// the stage, its own progress and remaining time, the job's elapsed time and its ETA: the
// running stage's remaining time (from its own rate once it has one, else its estimate minus
// its elapsed time) plus the estimates of the stages after it.
// A stage's rate is a RateEstimate (rate_estimate.hpp): it runs from the stage's first update
// on (work before it, a resumed run's earlier steps or the first step's kernel compilation,
// does not dilute it), and is known only once a few intervals after that update are timed.
// An estimate of < 0 means "not known yet": the ETA reads "?" until it is known.
// Output goes to stderr like Progress: one rewritten line on a terminal, plain lines at most
// every `plain_every_s` seconds otherwise. Time is read from `clock` (tests pass a fake one).
#pragma once
#include <string>
#include <vector>

#include "core/clock.hpp"
#include "core/rate_estimate.hpp"

namespace sgnlf {

class StagedProgress {
 public:
  StagedProgress(std::string label, std::vector<std::string> stages, double plain_every_s = 10.0,
                 SecondsClock clock = steady_seconds());
  ~StagedProgress();

  // The expected duration of `stage` in seconds (< 0: unknown). A finished stage ignores it.
  void estimate(size_t stage, double seconds);
  // Starts `stage` (its clock and counters); stages before it that were not ended count as
  // done earlier (a resumed job), with no time.
  void begin(size_t stage);
  // The running stage has `done` of `total` units.
  void update(long done, long total, const std::string& extra = "");
  // Ends the running stage: its measured time replaces its estimate.
  void end();
  // The last line, with the job's total time.
  void finish(const std::string& extra = "");

  // The running stage (-1: none).
  long current() const { return current_; }
  // Seconds until the running stage ends (its rate, else its estimate minus its elapsed
  // time); < 0 when unknown or no stage runs.
  double stage_eta_s() const;
  // The running stage's units per second by its rate; 0 while not known.
  double stage_units_per_s() const { return current_ >= 0 ? rate_.units_per_s() : 0.0; }
  // Seconds until the job ends by the current estimates; < 0 when some estimate is unknown.
  double eta_s() const;
  double elapsed_s() const;
  // The text of the line (no terminal codes).
  std::string line(const std::string& extra = "") const;

 private:
  struct Stage {
    std::string name;
    double estimate_s = -1.0;
    double measured_s = -1.0;  // ≥ 0 once ended
    bool ended = false;
  };
  double stage_elapsed_s() const;
  void print(const std::string& extra, bool force);

  std::string label_;
  std::vector<Stage> stages_;
  long current_ = -1;
  long done_ = 0, total_ = 0;
  RateEstimate rate_;  // the running stage's, from its first update
  double plain_every_s_;
  SecondsClock clock_;
  bool tty_;
  bool finished_ = false;
  double start_, stage_start_;
  double last_print_ = -1e9;
};

}  // namespace sgnlf
