// Deskewing a spinning LiDAR's sweep (motion compensation): a point measured τ seconds after
// the frame's reference time lies in the sensor frame of that moment; with the sensor moving at
// a constant body-frame velocity ξ over the sweep (rad/s, m/s; KISS-ICP's model, Vizzo et al.,
// RA-L 2023, §III-A) that frame is T_ref_lidar(τ) = Exp(τ ξ) in the reference frame, so
//   p_ref = Exp(τ_i ξ) · p_i,   τ_i = sweep_time_offset(timing, duration, p_i).
// The velocity comes from two pose estimates: ξ = Log(T_world_a⁻¹ T_world_b) / (t_b − t_a).
#pragma once
#include <vector>

#include "geometry/se3.hpp"
#include "geometry/sweep_timing.hpp"

namespace sgnlf {

// Constant body-frame velocity (ω, v) per second between two poses dt_s apart (dt_s > 0).
Vec6 constant_velocity_twist(const Pose& T_world_a, const Pose& T_world_b, double dt_s);

// The sensor pose at time offset tau_s from the reference, in the reference frame: Exp(τ ξ).
Pose sweep_pose(const Vec6& twist_per_s, double tau_s);

// Points of one sweep (LiDAR frame, each in the sensor frame of its own firing time) expressed
// in the LiDAR frame at the sweep's reference time. Any point order; duration_s = 1 / rate_hz.
std::vector<Vec3> deskew(const std::vector<Vec3>& points_lidar, const SweepTiming& timing,
                         double duration_s, const Vec6& twist_per_s);

}  // namespace sgnlf
