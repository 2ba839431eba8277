// Pose-only Adam and the decoupled-parameterisation chain rule.
#include "posegraph/pose_adam.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace sgnlf::posegraph {

Vec6 decoupled_gradient(const Pose& T_base, const Vec6& xi, const Vec6& g_pose) {
  Vec6 g;
  g.head<3>() = right_jacobian_so3(xi.head<3>()).transpose() * g_pose.head<3>();
  g.tail<3>() = T_base.linear().transpose() * g_pose.tail<3>();
  return g;
}

PoseAdam::PoseAdam(size_t frames, const AdamSettings& s)
    : s_(s), m_(frames, Vec6::Zero()), v_(frames, Vec6::Zero()) {}

void PoseAdam::step(std::vector<Vec6>& xi, const std::vector<Vec6>& grad_xi) {
  require(xi.size() == m_.size() && grad_xi.size() == m_.size(),
          "PoseAdam::step: " + std::to_string(xi.size()) + " parameters and " +
              std::to_string(grad_xi.size()) + " gradients for " + std::to_string(m_.size()) +
              " frames");
  ++t_;
  const double c1 = 1.0 - std::pow(s_.beta1, t_), c2 = 1.0 - std::pow(s_.beta2, t_);
  for (size_t k = 0; k < xi.size(); ++k)
    for (int d = 0; d < 6; ++d) {
      const double g = grad_xi[k][d];
      m_[k][d] = s_.beta1 * m_[k][d] + (1.0 - s_.beta1) * g;
      v_[k][d] = s_.beta2 * v_[k][d] + (1.0 - s_.beta2) * g * g;
      const double lr = d < 3 ? s_.lr_rotation : s_.lr_translation;
      xi[k][d] -= lr * (m_[k][d] / c1) / (std::sqrt(v_[k][d] / c2) + s_.eps);
    }
}

}  // namespace sgnlf::posegraph
