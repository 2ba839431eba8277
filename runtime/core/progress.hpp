// Progress reporting on stderr: a single rewritten line on a terminal, plain periodic lines
// otherwise (CI logs, pipes). Shows rate, ETA and caller-provided fields such as the loss.
#pragma once
#include <chrono>
#include <string>

namespace sgnlf {

class Progress {
 public:
  // Steps `first` (a resumed run's step, else 0) to `total` of `label`; plain-mode lines at
  // most every `plain_every_s` seconds. The rate counts only the steps this process ran.
  Progress(std::string label, long total, double plain_every_s = 10.0, long first = 0);
  ~Progress();
  // Reports that `done` steps are complete; `extra` is appended (e.g. "loss 0.0123").
  void update(long done, const std::string& extra = "");
  void finish(const std::string& extra = "");
  // Restarts the rate's clock at `done` steps: work before the first step (a geometric stage)
  // does not count as the steps' time.
  void restart_clock(long done);
  double elapsed_s() const;

  // The line update() prints (without `extra`): rate = (done - first) / elapsed_s.
  static std::string line(const std::string& label, long first, long done, long total,
                          double elapsed_s);

 private:
  std::string label_;
  long total_, first_;
  double plain_every_s_;
  bool tty_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  double last_print_ = -1e9;
};

std::string format_duration(double seconds);

}  // namespace sgnlf
