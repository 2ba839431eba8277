// StagedProgress (see staged_progress.hpp).
#include "core/staged_progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>

#include "core/error.hpp"
#include "core/progress.hpp"

namespace sgnlf {

StagedProgress::StagedProgress(std::string label, std::vector<std::string> stages,
                               double plain_every_s, SecondsClock clock)
    : label_(std::move(label)),
      plain_every_s_(plain_every_s),
      clock_(std::move(clock)),
      tty_(isatty(STDERR_FILENO) != 0) {
  require(!stages.empty(), "StagedProgress: no stages");
  require(bool(clock_), "StagedProgress: no clock");
  for (auto& s : stages) stages_.push_back(Stage{std::move(s)});
  start_ = stage_start_ = clock_();
}

StagedProgress::~StagedProgress() {
  if (!finished_ && tty_ && last_print_ > -1e9) std::cerr << "\n";
}

double StagedProgress::elapsed_s() const { return clock_() - start_; }

double StagedProgress::stage_elapsed_s() const { return clock_() - stage_start_; }

void StagedProgress::estimate(size_t stage, double seconds) {
  require(stage < stages_.size(), "StagedProgress::estimate: stage " + std::to_string(stage));
  stages_[stage].estimate_s = seconds;
}

void StagedProgress::begin(size_t stage) {
  require(stage < stages_.size(), "StagedProgress::begin: stage " + std::to_string(stage));
  for (size_t k = 0; k < stage; ++k)
    if (!stages_[k].ended) {
      stages_[k].ended = true;
      stages_[k].measured_s = 0.0;
    }
  current_ = long(stage);
  done_ = total_ = 0;
  rate_.reset();
  stage_start_ = clock_();
  print("", true);
}

void StagedProgress::update(long done, long total, const std::string& extra) {
  if (current_ < 0) return;
  rate_.add(clock_(), done);
  done_ = done;
  total_ = total;
  print(extra, false);
}

void StagedProgress::end() {
  if (current_ < 0) return;
  Stage& s = stages_[size_t(current_)];
  s.ended = true;
  s.measured_s = stage_elapsed_s();
  current_ = -1;
}

double StagedProgress::stage_eta_s() const {
  if (current_ < 0) return -1.0;
  if (total_ > 0 && rate_.known()) return rate_.remaining_s(total_);
  const Stage& s = stages_[size_t(current_)];
  if (s.estimate_s < 0) return -1.0;
  return std::max(0.0, s.estimate_s - stage_elapsed_s());
}

double StagedProgress::eta_s() const {
  double eta = 0.0;
  for (size_t k = 0; k < stages_.size(); ++k) {
    const Stage& s = stages_[k];
    if (s.ended) continue;
    const double t = long(k) == current_ ? stage_eta_s() : s.estimate_s;
    if (t < 0) return -1.0;
    eta += t;
  }
  return eta;
}

std::string StagedProgress::line(const std::string& extra) const {
  std::string stage = "starting";
  if (current_ >= 0) {
    stage = stages_[size_t(current_)].name;
    if (total_ > 0) stage += " " + std::to_string(done_) + "/" + std::to_string(total_);
    const double left = stage_eta_s();
    if (left >= 0) stage += ", " + format_duration(left) + " left";
  }
  char buf[400];
  std::snprintf(buf, sizeof buf, "%s [%ld/%zu %s] elapsed %s ETA %s", label_.c_str(),
                current_ >= 0 ? current_ + 1 : 0, stages_.size(), stage.c_str(),
                format_duration(elapsed_s()).c_str(), format_duration(eta_s()).c_str());
  return std::string(buf) + (extra.empty() ? "" : " | " + extra);
}

void StagedProgress::print(const std::string& extra, bool force) {
  const double t = elapsed_s();
  if (!force) {
    if (!tty_ && t - last_print_ < plain_every_s_) return;
    if (tty_ && t - last_print_ < 0.2) return;
  }
  last_print_ = t;
  if (tty_)
    std::cerr << "\r\033[K" << line(extra) << std::flush;
  else
    std::cerr << line(extra) << "\n";
}

void StagedProgress::finish(const std::string& extra) {
  if (finished_) return;
  finished_ = true;
  char buf[200];
  std::snprintf(buf, sizeof buf, "%s done in %s", label_.c_str(), format_duration(elapsed_s()).c_str());
  std::cerr << (tty_ ? "\r\033[K" : "") << buf << (extra.empty() ? "" : " | " + extra) << "\n";
}

}  // namespace sgnlf
