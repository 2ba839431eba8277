// AdaptiveThreshold (see adaptive_threshold.hpp).
#include "odometry/adaptive_threshold.hpp"

#include <cmath>

namespace sgnlf::odometry {

double AdaptiveThreshold::model_error(const Pose& deviation) const {
  const double theta = rotation_angle(deviation.linear());
  return deviation.translation().norm() + 2.0 * max_range_ * std::sin(0.5 * theta);
}

void AdaptiveThreshold::update(const Pose& deviation) {
  const double e = model_error(deviation);
  if (e > min_motion_) {
    sse_ += e * e;
    ++samples_;
  }
}

double AdaptiveThreshold::sigma() const {
  return samples_ < 1 ? initial_ : std::sqrt(sse_ / samples_);
}

}  // namespace sgnlf::odometry
