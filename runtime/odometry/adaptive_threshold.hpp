// KISS-ICP's adaptive correspondence threshold (Vizzo et al., RA-L 2023, §III-C): the model
// deviation ΔT = T_pred⁻¹ · T_reg of each registered frame becomes a point displacement bound
// δ = ‖Δt‖ + 2 r_max sin(θ/2) (eq. 5, θ the angle of ΔR), and σ is the root mean square of
// the δ that exceed `min_motion` (eq. 6); `initial_threshold` until there is one.
#pragma once
#include "geometry/se3.hpp"

namespace sgnlf::odometry {

class AdaptiveThreshold {
 public:
  AdaptiveThreshold(double initial_threshold, double min_motion, double max_range)
      : initial_(initial_threshold), min_motion_(min_motion), max_range_(max_range) {}

  // eq. 5
  double model_error(const Pose& deviation) const;
  void update(const Pose& deviation);
  double sigma() const;  // eq. 6
  int samples() const { return samples_; }

 private:
  double initial_, min_motion_, max_range_;
  double sse_ = 0.0;
  int samples_ = 0;
};

}  // namespace sgnlf::odometry
