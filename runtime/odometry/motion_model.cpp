// predict_constant_velocity (see motion_model.hpp).
#include "odometry/motion_model.hpp"

#include "core/error.hpp"

namespace sgnlf::odometry {

Pose predict_constant_velocity(const std::vector<Pose>& poses, const std::vector<double>& timestamps,
                               double t_next) {
  if (poses.size() != timestamps.size()) throw Error("predict_constant_velocity: size mismatch");
  if (poses.empty()) return Pose::Identity();
  const size_t n = poses.size();
  if (n < 2) return poses.back();
  const Pose delta = poses[n - 2].inverse() * poses[n - 1];
  const double dt_prev = timestamps[n - 1] - timestamps[n - 2];
  const double dt_next = t_next - timestamps[n - 1];
  if (!(dt_prev > 0) || !(dt_next > 0)) return poses.back() * delta;
  const double s = dt_next / dt_prev;
  return poses.back() * exp_se3(s * log_se3(delta));
}

}  // namespace sgnlf::odometry
