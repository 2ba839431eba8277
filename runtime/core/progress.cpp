#include "core/progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>

#include "core/error.hpp"

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

Progress::Progress(std::string label, long total, double plain_every_s, long first, SecondsClock clock)
    : label_(std::move(label)),
      total_(total),
      first_(first),
      done_(first),
      plain_every_s_(plain_every_s),
      clock_(std::move(clock)),
      tty_(isatty(STDERR_FILENO) != 0) {
  require(bool(clock_), "Progress: no clock");
  start_ = clock_();
  rate_.add(start_, first_);
}

Progress::~Progress() {
  if (!finished_ && tty_) std::cerr << "\n";
}

double Progress::elapsed_s() const { return clock_() - start_; }

void Progress::restart_clock(long done) {
  start_ = clock_();
  first_ = done_ = done;
  rate_.reset();
  rate_.add(start_, done);
  last_print_ = -1e9;
}

std::string Progress::line(const std::string& label, long done, long total, double rate, double eta_s) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s %ld/%ld (%.0f%%) %.2f it/s ETA %s", label.c_str(), done,
                total, total > 0 ? 100.0 * double(done) / double(total) : 100.0, rate,
                format_duration(eta_s).c_str());
  return buf;
}

std::string Progress::line() const { return line(label_, done_, total_, rate_.units_per_s(), eta_s()); }

void Progress::update(long done, const std::string& extra) {
  rate_.add(clock_(), done);
  done_ = done;
  const double t = elapsed_s();
  if (!tty_ && t - last_print_ < plain_every_s_ && done < total_) return;
  if (tty_ && t - last_print_ < 0.2 && done < total_) return;
  last_print_ = t;
  const std::string buf = line();
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
