// Constant-velocity prediction (KISS-ICP §III-A): the next pose continues the last relative
// motion, scaled by the ratio of the time steps when they differ (nuScenes keyframes are
// 0.45–0.55 s apart): T_pred = T_{k−1} · Exp(s · Log(T_{k−2}⁻¹ T_{k−1})), s = Δt_k / Δt_{k−1}.
#pragma once
#include <vector>

#include "geometry/se3.hpp"

namespace sgnlf::odometry {

// `poses` and `timestamps` of the frames so far (same length); the prediction for a frame at
// `t_next`. Identity motion with fewer than two poses; s = 1 when timestamps do not increase.
Pose predict_constant_velocity(const std::vector<Pose>& poses, const std::vector<double>& timestamps,
                               double t_next);

}  // namespace sgnlf::odometry
