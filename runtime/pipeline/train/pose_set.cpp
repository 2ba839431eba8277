// PoseSet (see pose_set.hpp).
#include "pipeline/train/pose_set.hpp"

#include <cmath>

#include "core/error.hpp"

namespace sgnlf::pipeline {

PoseSet::PoseSet(std::vector<Pose> T_init, const PoseOptimConfig& c, double lr_scale)
    : T_init_(std::move(T_init)),
      cfg_(c),
      lr_scale_(lr_scale),
      xi_(T_init_.size(), Vec6::Zero()),
      m_(T_init_.size(), Vec6::Zero()),
      v_(T_init_.size(), Vec6::Zero()),
      t_(T_init_.size(), 0),
      pending_(T_init_.size(), Vec6::Zero()),
      pending_on_(T_init_.size(), 0) {}

Pose PoseSet::pose(size_t i) const { return corrected_pose(T_init_.at(i), xi_.at(i)); }

std::vector<Pose> PoseSet::poses() const {
  std::vector<Pose> out;
  for (size_t i = 0; i < size(); ++i) out.push_back(pose(i));
  return out;
}

void PoseSet::add_pending(size_t i, const Vec6& g) {
  if (!g.allFinite())
    throw NumericError("pending pose gradient of frame index " + std::to_string(i) +
                       " is not finite");
  pending_.at(i) += g;
  pending_on_.at(i) = 1;
}

std::vector<double> PoseSet::pending_flat() const {
  std::vector<double> f;
  for (size_t i = 0; i < size(); ++i) {
    f.push_back(double(pending_on_[i]));
    f.insert(f.end(), pending_[i].data(), pending_[i].data() + 6);
  }
  return f;
}

void PoseSet::set_pending_flat(const std::vector<double>& flat) {
  require(flat.size() == 7 * size(), "PoseSet: pending state of " + std::to_string(flat.size()) +
                                         " numbers for " + std::to_string(size()) + " frames");
  for (size_t i = 0; i < size(); ++i) {
    pending_on_[i] = flat[7 * i] != 0.0 ? 1 : 0;
    for (int k = 0; k < 6; ++k) pending_[i][k] = flat[7 * i + 1 + size_t(k)];
  }
}

void PoseSet::step(size_t i, const Vec6& g_step, double progress) {
  // Bit-identical without a pending gradient: g is g_step itself.
  const Vec6 g = pending_on_.at(i) ? Vec6(g_step + pending_[i]) : g_step;
  pending_[i].setZero();
  pending_on_[i] = 0;
  if (!g.allFinite())
    throw NumericError("pose gradient of frame index " + std::to_string(i) + " is not finite");
  const double decay = std::pow(cfg_.final_factor, std::min(1.0, std::max(0.0, progress)));
  const double lr[2] = {cfg_.lr_rot * decay * lr_scale_, cfg_.lr_trans * decay * lr_scale_};
  const long t = ++t_.at(i);
  const double c1 = 1.0 - std::pow(cfg_.beta1, double(t)), c2 = 1.0 - std::pow(cfg_.beta2, double(t));
  for (int k = 0; k < 6; ++k) {
    m_[i][k] = cfg_.beta1 * m_[i][k] + (1.0 - cfg_.beta1) * g[k];
    v_[i][k] = cfg_.beta2 * v_[i][k] + (1.0 - cfg_.beta2) * g[k] * g[k];
    xi_[i][k] -= lr[k / 3] * (m_[i][k] / c1) / (std::sqrt(v_[i][k] / c2) + cfg_.eps);
  }
}

void PoseSet::set_pose(size_t i, const Pose& T) {
  if (!T.matrix().allFinite())
    throw NumericError("set_pose: pose of frame index " + std::to_string(i) + " is not finite");
  const Pose& A = T_init_.at(i);
  Vec6 xi;
  xi.head<3>() = log_so3(A.rotation().transpose() * T.rotation());
  xi.tail<3>() = A.rotation().transpose() * (T.translation() - A.translation());
  xi_[i] = xi;
}

std::vector<Vec6> PoseSet::to_vec6(const std::vector<double>& flat) const {
  require(flat.size() == 6 * size(), "PoseSet: state of " + std::to_string(flat.size()) +
                                         " numbers for " + std::to_string(size()) + " frames");
  std::vector<Vec6> out(size());
  for (size_t i = 0; i < size(); ++i)
    for (int k = 0; k < 6; ++k) out[i][k] = flat[6 * i + size_t(k)];
  return out;
}

std::vector<std::pair<std::string, std::vector<float>>> PoseSet::state_arrays() const {
  auto flat = [](const std::vector<Vec6>& v) {
    std::vector<double> f;
    for (const auto& x : v) f.insert(f.end(), x.data(), x.data() + 6);
    return f;
  };
  std::vector<double> t(t_.begin(), t_.end());
  return {{"poses.xi", pack_doubles(flat(xi_))},
          {"poses.adam_m", pack_doubles(flat(m_))},
          {"poses.adam_v", pack_doubles(flat(v_))},
          {"poses.adam_t", pack_doubles(t)}};
}

}  // namespace sgnlf::pipeline
