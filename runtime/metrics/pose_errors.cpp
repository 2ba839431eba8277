// Umeyama SE(3) alignment, ATE and RPE (protocol §4; see pose_errors.hpp).
#include "metrics/pose_errors.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace sgnlf::metrics {
namespace {

void check_pose(const Pose& T, const char* which, size_t i) {
  require(T.matrix().allFinite(),
          std::string("pose metrics: ") + which + " pose " + std::to_string(i) + " is not finite");
}

}  // namespace

Pose umeyama_se3(const std::vector<Vec3>& p_est, const std::vector<Vec3>& p_gt) {
  require(p_est.size() == p_gt.size(),
          "umeyama_se3: " + std::to_string(p_est.size()) + " estimated positions vs " +
              std::to_string(p_gt.size()) + " ground-truth positions");
  require(!p_est.empty(), "umeyama_se3: no positions");
  const double n = double(p_est.size());
  Vec3 mu_est = Vec3::Zero(), mu_gt = Vec3::Zero();
  for (size_t i = 0; i < p_est.size(); ++i) {
    mu_est += p_est[i];
    mu_gt += p_gt[i];
  }
  mu_est /= n;
  mu_gt /= n;
  // Umeyama (1991) eq. 38–40: C = 1/n Σ (gt − μ_gt)(est − μ_est)ᵀ = U D Vᵀ, R = U S Vᵀ.
  Mat3 C = Mat3::Zero();
  for (size_t i = 0; i < p_est.size(); ++i)
    C += (p_gt[i] - mu_gt) * (p_est[i] - mu_est).transpose();
  C /= n;
  Eigen::JacobiSVD<Mat3> svd(C, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 S = Mat3::Identity();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) S(2, 2) = -1.0;
  Pose T = Pose::Identity();
  T.linear() = svd.matrixU() * S * svd.matrixV().transpose();
  T.translation() = mu_gt - T.linear() * mu_est;  // scale fixed to 1
  return T;
}

bool is_planar(const std::vector<Pose>& poses) {
  if (poses.empty()) return false;
  double lo = poses.front().translation().z(), hi = lo;
  for (const Pose& T : poses) {
    lo = std::min(lo, T.translation().z());
    hi = std::max(hi, T.translation().z());
  }
  return hi - lo <= kPlanarReferenceTolM;
}

PoseErrors compute_pose_errors(const std::vector<Pose>& est, const std::vector<Pose>& gt) {
  require(est.size() == gt.size(),
          "pose metrics: " + std::to_string(est.size()) + " estimated poses vs " +
              std::to_string(gt.size()) + " ground-truth poses");
  require(est.size() >= 2, "pose metrics: need at least 2 poses, got " +
                               std::to_string(est.size()));
  std::vector<Vec3> p_est(est.size()), p_gt(gt.size());
  for (size_t i = 0; i < est.size(); ++i) {
    check_pose(est[i], "estimated", i);
    check_pose(gt[i], "ground-truth", i);
    p_est[i] = est[i].translation();
    p_gt[i] = gt[i].translation();
  }
  const Pose T_gt_est = umeyama_se3(p_est, p_gt);
  std::vector<Pose> aligned(est.size());
  for (size_t i = 0; i < est.size(); ++i) aligned[i] = T_gt_est * est[i];

  PoseErrors e;
  double se = 0.0, se_h = 0.0;
  for (size_t i = 0; i < est.size(); ++i) {
    const Vec3 d = gt[i].translation() - aligned[i].translation();
    se += d.squaredNorm();
    se_h += d.head<2>().squaredNorm();
  }
  e.ate_m = std::sqrt(se / double(est.size()));
  e.ate_h_m = std::sqrt(se_h / double(est.size()));
  e.planar_reference = is_planar(gt);

  double sum_t = 0.0, sum_r = 0.0;
  for (size_t i = 0; i + 1 < est.size(); ++i) {
    const Pose A_rel = aligned[i].inverse() * aligned[i + 1];
    const Pose B_rel = gt[i].inverse() * gt[i + 1];
    const Pose E = A_rel.inverse() * B_rel;
    sum_t += E.translation().norm();
    sum_r += rotation_angle(E.linear());
  }
  const double pairs = double(est.size() - 1);
  e.rpe_t_cm = 100.0 * sum_t / pairs;
  e.rpe_r_deg = sum_r / pairs * 180.0 / M_PI;
  return e;
}

}  // namespace sgnlf::metrics
