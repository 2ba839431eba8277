// Progress reporting on stderr: a single rewritten line on a terminal, plain periodic lines
// otherwise (CI logs, pipes). Shows rate, ETA and caller-provided fields such as the loss.
#pragma once
#include <chrono>
#include <string>

namespace sgnlf {

class Progress {
 public:
  // `total` steps of `label`; plain-mode lines at most every `plain_every_s` seconds.
  Progress(std::string label, long total, double plain_every_s = 10.0);
  ~Progress();
  // Reports that `done` steps are complete; `extra` is appended (e.g. "loss 0.0123").
  void update(long done, const std::string& extra = "");
  void finish(const std::string& extra = "");
  double elapsed_s() const;

 private:
  std::string label_;
  long total_;
  double plain_every_s_;
  bool tty_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  double last_print_ = -1e9;
};

std::string format_duration(double seconds);

}  // namespace sgnlf
