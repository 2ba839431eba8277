// Deskewing (see deskew.hpp).
#include "geometry/deskew.hpp"

#include <cmath>

#include "core/error.hpp"

namespace sgnlf {

Vec6 constant_velocity_twist(const Pose& T_world_a, const Pose& T_world_b, double dt_s) {
  if (!(dt_s > 0) || !std::isfinite(dt_s))
    throw Error("constant_velocity_twist: time step " + std::to_string(dt_s) + " s is not positive");
  return log_se3(T_world_a.inverse() * T_world_b) / dt_s;
}

Pose sweep_pose(const Vec6& twist_per_s, double tau_s) { return exp_se3(tau_s * twist_per_s); }

std::vector<Vec3> deskew(const std::vector<Vec3>& points_lidar, const SweepTiming& timing,
                         double duration_s, const Vec6& twist_per_s) {
  if (!(duration_s >= 0) || !std::isfinite(duration_s))
    throw Error("deskew: sweep duration " + std::to_string(duration_s) + " s");
  std::vector<Vec3> out(points_lidar.size());
  if (twist_per_s.isZero(0.0) || duration_s == 0.0) {
    out = points_lidar;
    return out;
  }
  for (size_t i = 0; i < points_lidar.size(); ++i) {
    const Vec3& p = points_lidar[i];
    out[i] = sweep_pose(twist_per_s, sweep_time_offset(timing, duration_s, p)) * p;
  }
  return out;
}

}  // namespace sgnlf
