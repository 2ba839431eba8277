// Trajectory errors of estimated poses against ground truth (protocol §4, GeoNLF's
// utils/SIM3/sim3.py):
//   alignment: Umeyama on the positions with the scale fixed to 1 (a clean SE(3) alignment
//     T_align = argmin Σ‖p_gt − (R·p_est + t)‖², t = μ_gt − R·μ_est), applied to every
//     estimated pose. GeoNLF instead keeps t = μ_gt − s·R·μ_est with the estimated Sim(3)
//     scale s and then sets s = 1; we implement the clean alignment (protocol §4 says so).
//   ATE   = sqrt(mean_i ‖p_gt,i − p_aligned,i‖²), metres.
//   ATE_h = the same over the x, y components only, under the same 3D alignment (not a
//     separate 2D one): what planar reference poses (nuScenes' ego poses, z = 0) can judge.
//   RPE   over consecutive pairs: E = inv(inv(A_i)·A_{i+1}) · (inv(B_i)·B_{i+1}) with A the
//     aligned estimate and B the ground truth; RPE_t = mean ‖trans(E)‖ in cm,
//     RPE_r = mean arccos((tr R_E − 1)/2) in degrees.
#pragma once
#include <vector>

#include "geometry/se3.hpp"

namespace sgnlf::metrics {

struct PoseErrors {
  double ate_m = 0.0;
  double ate_h_m = 0.0;  // horizontal (x, y) ATE, same alignment
  double rpe_t_cm = 0.0;
  double rpe_r_deg = 0.0;
  // Every ground-truth z equal within kPlanarReferenceTolM: the reference supports the
  // horizontal ATE only ("ate_reference": "horizontal", else "3d").
  bool planar_reference = false;
};

constexpr double kPlanarReferenceTolM = 1e-6;

// True when every pose's z lies within kPlanarReferenceTolM of every other's (false when empty).
bool is_planar(const std::vector<Pose>& poses);

// T_gt_est (rotation + translation, no scale) minimising the squared position error.
// Needs ≥ 1 pose pair; with < 3 non-collinear positions the rotation is not unique and the
// SVD's choice is returned.
Pose umeyama_se3(const std::vector<Vec3>& p_est, const std::vector<Vec3>& p_gt);

// Aligns `est` to `gt` (umeyama_se3 on the positions) and measures ATE and RPE. Needs equal
// sizes and ≥ 2 poses.
PoseErrors compute_pose_errors(const std::vector<Pose>& est, const std::vector<Pose>& gt);

}  // namespace sgnlf::metrics
