// RateEstimate (see rate_estimate.hpp).
#include "core/rate_estimate.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace sgnlf {

RateEstimate::RateEstimate(int min_intervals) : min_intervals_(min_intervals) {
  require(min_intervals >= 1, "RateEstimate: min_intervals " + std::to_string(min_intervals) + " < 1");
}

void RateEstimate::reset() { samples_.clear(); }

void RateEstimate::add(double t_s, long done) {
  if (!samples_.empty() && done <= samples_.back().done) return;
  samples_.push_back({t_s, done});
}

bool RateEstimate::known() const { return long(samples_.size()) > long(min_intervals_); }

double RateEstimate::seconds_per_unit() const {
  if (!known()) return -1.0;
  const Sample& a = samples_[(samples_.size() - 1) / 2];
  const Sample& b = samples_.back();
  return std::max(0.0, b.t - a.t) / double(b.done - a.done);
}

double RateEstimate::units_per_s() const {
  const double spu = seconds_per_unit();
  return spu > 0.0 ? 1.0 / spu : 0.0;
}

double RateEstimate::remaining_s(long total) const {
  if (!known()) return -1.0;
  return double(std::max(0L, total - samples_.back().done)) * seconds_per_unit();
}

}  // namespace sgnlf
