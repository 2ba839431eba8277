#include "core/progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>

namespace sgnlf {

std::string format_duration(double s) {
  char buf[32];
  if (s < 0 || s > 1e7) return "?";
  const long t = long(s + 0.5);
  if (t >= 3600)
    std::snprintf(buf, sizeof buf, "%ldh%02ldm", t / 3600, (t / 60) % 60);
  else
    std::snprintf(buf, sizeof buf, "%ldm%02lds", t / 60, t % 60);
  return buf;
}

Progress::Progress(std::string label, long total, double plain_every_s, long first)
    : label_(std::move(label)),
      total_(total),
      first_(first),
      plain_every_s_(plain_every_s),
      tty_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() {
  if (!finished_ && tty_) std::cerr << "\n";
}

double Progress::elapsed_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::restart_clock(long done) {
  start_ = std::chrono::steady_clock::now();
  first_ = done;
  last_print_ = -1e9;
}

std::string Progress::line(const std::string& label, long first, long done, long total,
                           double t) {
  const double rate = t > 0 ? double(done - first) / t : 0.0;
  const double eta = rate > 0 ? double(total - done) / rate : -1.0;
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s %ld/%ld (%.0f%%) %.2f it/s ETA %s", label.c_str(), done,
                total, total > 0 ? 100.0 * double(done) / double(total) : 100.0, rate,
                format_duration(eta).c_str());
  return buf;
}

void Progress::update(long done, const std::string& extra) {
  const double t = elapsed_s();
  if (!tty_ && t - last_print_ < plain_every_s_ && done < total_) return;
  if (tty_ && t - last_print_ < 0.2 && done < total_) return;
  last_print_ = t;
  const std::string buf = line(label_, first_, done, total_, t);
  if (tty_)
    std::cerr << "\r\033[K" << buf << (extra.empty() ? "" : " | ") << extra << std::flush;
  else
    std::cerr << buf << (extra.empty() ? "" : " | ") << extra << "\n";
}

void Progress::finish(const std::string& extra) {
  if (finished_) return;
  finished_ = true;
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s done: %ld steps in %s", label_.c_str(), total_ - first_,
                format_duration(elapsed_s()).c_str());
  std::cerr << (tty_ ? "\r\033[K" : "") << buf << (extra.empty() ? "" : " | ") << extra << "\n";
}

}  // namespace sgnlf
