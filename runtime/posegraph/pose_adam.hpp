// Pose-only Adam over the decoupled corrections ξ_k = (ω_k, u_k) of every frame (method.md §0:
// T_k = T_base,k · [Exp_SO3(ω_k) | u_k], translation without the left Jacobian), and the chain
// rule from a pose gradient (dL/dθ right rotation perturbation, dL/dt world translation) to ξ:
//   dL/dω = J_r(ω)ᵀ · dL/dθ      (R_base Exp(ω + δ) ≈ R Exp(J_r(ω) δ))
//   dL/du = R_baseᵀ · dL/dt       (t = R_base u + t_base)
// Separate learning rates for rotation (rad) and translation (m); no frame is held fixed.
#pragma once
#include <vector>

#include "geometry/se3.hpp"

namespace sgnlf::posegraph {

// dL/dξ of T = corrected_pose(T_base, ξ) from g = (dL/dθ, dL/dt) at that T.
Vec6 decoupled_gradient(const Pose& T_base, const Vec6& xi, const Vec6& g_pose);

struct AdamSettings {
  double lr_rotation = 5e-3;     // rad per step (Adam's step is ≈ lr at most)
  double lr_translation = 2e-2;  // m per step
  double beta1 = 0.9, beta2 = 0.999, eps = 1e-12;
};

class PoseAdam {
 public:
  PoseAdam(size_t frames, const AdamSettings& s);
  // One step on every frame's ξ with its gradient dL/dξ (bias-corrected moments).
  void step(std::vector<Vec6>& xi, const std::vector<Vec6>& grad_xi);
  int steps() const { return t_; }

 private:
  AdamSettings s_;
  std::vector<Vec6> m_, v_;
  int t_ = 0;
};

}  // namespace sgnlf::posegraph
