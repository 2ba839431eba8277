// CrossFrameReprojection: launchers of kernels/render/reproject.cl and the host side of the
// backward pass (the fixed-order sum of the per-group partials and the map to dL/dξ).
#include "render/cross_frame_reprojection.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <sstream>

#include "core/error.hpp"
#include "geometry/pixel_boundaries.hpp"
#include "geometry/range_image.hpp"
#include "render/launch.hpp"

namespace sgnlf::render {

namespace {
// The backward's work-group size and the partials per group: fixed on every device, so that
// the gradient sums run in the same order everywhere (every OpenCL device allows 64).
constexpr size_t kBwdGroup = 64;
constexpr int kPartials = 6;

std::string num(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

// Throws naming the launcher and argument when `b` holds fewer than `n` 4-byte words.
void check_words(const cl::Buffer& b, size_t n, const std::string& what) {
  if (!b || b.bytes() < n * 4)
    throw Error(what + ": buffer has " + std::to_string(b ? b.bytes() / 4 : 0) +
                " 4-byte elements, needs " + std::to_string(n));
}

cl_float4 row4(const std::array<float, 12>& r, int k) {
  cl_float4 v;
  for (int c = 0; c < 4; ++c) v.s[c] = r[size_t(4 * k + c)];
  return v;
}

std::vector<float> to_float(const std::vector<double>& v) { return {v.begin(), v.end()}; }
}  // namespace

std::array<float, 12> lidarj_lidari_rows(const Pose& T_lidarj_lidari) {
  std::array<float, 12> r{};
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 4; ++c) r[size_t(4 * k + c)] = float(T_lidarj_lidari.matrix()(k, c));
  return r;
}

void check_rigid(const Pose& T, const std::string& what) {
  const Eigen::Matrix4d& M = T.matrix();
  if (!M.allFinite()) {
    std::ostringstream s;
    s << M;
    throw NumericError(what + " is not finite:\n" + s.str());
  }
  const Mat3 R = M.topLeftCorner<3, 3>();
  const double orth = (R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff();
  const double det = R.determinant();
  const double bottom = (M.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff();
  if (orth > 1e-6 || det <= 0.0 || bottom != 0.0)
    throw Error(what + " is not a rigid transform: max |RᵀR − I| = " + num(orth) + ", det R = " +
                num(det) + ", max |bottom row − (0 0 0 1)| = " + num(bottom) +
                " (allowed: 1e-6, > 0, 0)");
}

CrossFrameReprojection::CrossFrameReprojection(cl::Runtime& rt, const Sensor& sensor_i,
                                               const Sensor& sensor_j, double range_scale)
    : rt_(rt), sensor_i_(sensor_i), sensor_j_(sensor_j) {
  sensor_i_.validate();
  const PixelBoundaries bj = pixel_boundaries(sensor_j_);  // validates sensor j
  if (!(range_scale > 0.0) || !std::isfinite(range_scale))
    throw ConfigError("CrossFrameReprojection: range_scale = " + num(range_scale) +
                      " depth units per metre; must be positive and finite");
  if (rt.device().max_work_group_size < kBwdGroup)
    throw Error("CrossFrameReprojection: device '" + rt.device().name + "' allows work-groups of " +
                std::to_string(rt.device().max_work_group_size) + ", the backward needs " +
                std::to_string(kBwdGroup));
  n_src_ = sensor_i_.height * sensor_i_.width;
  n_dst_ = sensor_j_.height * sensor_j_.width;
  // Squared range limits, rounded to float once (the host mirror in the tests does the same).
  const double lo = sensor_j_.min_range_m * range_scale, hi = sensor_j_.max_range_m * range_scale;
  min_q_ = float(lo * lo);
  max_q_ = float(hi * hi);
  if (!std::isfinite(max_q_) || !(max_q_ > min_q_))
    throw ConfigError("CrossFrameReprojection: range limits " + num(lo) + " … " + num(hi) +
                      " depth units give no usable squared range in float");
  // The backward's groups: a fixed function of the image size (≈ 16 pixels per work-item).
  bwd_groups_ = int(std::clamp<long>((long(n_dst_) + 1023) / 1024, 1, 256));
  bwd_chunk_ = (n_dst_ + bwd_groups_ - 1) / bwd_groups_;

  dirs_i_ = cl::Buffer::from(rt, ray_directions(sensor_i_));
  col_tab_ = cl::Buffer::from(rt, to_float(bj.col));
  row_tab_ = cl::Buffer::from(rt, to_float(bj.row));
  key_ = cl::Buffer(rt, size_t(n_dst_) * 4);
  src_target_ = cl::Buffer(rt, size_t(n_src_) * 4);
  src_key_ = cl::Buffer(rt, size_t(n_src_) * 4);
  partial_ = cl::Buffer(rt, size_t(bwd_groups_) * kPartials * 4);
  const std::string file = "render/reproject.cl";
  clear_k_ = rt.kernel(file, "render_reproject_fwd_clear");
  zmin_k_ = rt.kernel(file, "render_reproject_fwd_zmin");
  winner_k_ = rt.kernel(file, "render_reproject_fwd_winner");
  resolve_k_ = rt.kernel(file, "render_reproject_fwd_resolve");
  bwd_clear_k_ = rt.kernel(file, "render_reproject_bwd_clear");
  bwd_k_ = rt.kernel(file, "render_reproject_bwd", "-DREPROJ_BWD_WG=" + std::to_string(kBwdGroup));
}

ReprojectionOutput CrossFrameReprojection::make_output() const {
  const size_t n = size_t(n_dst_) * 4;
  return {cl::Buffer(rt_, n), cl::Buffer(rt_, n), cl::Buffer(rt_, n), cl::Buffer(rt_, 2 * 4)};
}

void CrossFrameReprojection::check_output(const ReprojectionOutput& out,
                                          const std::string& what) const {
  check_words(out.range, size_t(n_dst_), what + " range (D_ij)");
  check_words(out.mask, size_t(n_dst_), what + " mask (M_ij)");
  check_words(out.winner, size_t(n_dst_), what + " winner");
  check_words(out.status, 2, what + " status");
}

ReprojectionContext CrossFrameReprojection::forward(const cl::Buffer& depth_i,
                                                    const Pose& T_world_lidar_i,
                                                    const Pose& T_world_lidar_j,
                                                    ReprojectionOutput& out) {
  const std::string what = "CrossFrameReprojection::forward";
  check_words(depth_i, size_t(n_src_), what + " depth_i (" + std::to_string(sensor_i_.height) +
                                           " x " + std::to_string(sensor_i_.width) + ")");
  check_output(out, what);
  check_rigid(T_world_lidar_i, what + ": T_world_lidar_i");
  check_rigid(T_world_lidar_j, what + ": T_world_lidar_j");
  ReprojectionContext ctx;
  ctx.T_world_lidar_i = T_world_lidar_i;
  ctx.T_world_lidar_j = T_world_lidar_j;
  ctx.T_lidarj_lidari = T_world_lidar_j.inverse(Eigen::Isometry) * T_world_lidar_i;
  ctx.rows_lidarj_lidari = lidarj_lidari_rows(ctx.T_lidarj_lidari);
  const auto& r = ctx.rows_lidarj_lidari;
  const float fov_up_rad = float(sensor_j_.fov_up_deg * M_PI / 180.0);
  const float inv_row_step = float(sensor_j_.height / (sensor_j_.fov_deg * M_PI / 180.0));

  clear_k_.set_args(n_dst_, key_, out.winner, out.status);
  launch_1d(clear_k_, size_t(n_dst_));
  zmin_k_.set_args(n_src_, depth_i, dirs_i_, row4(r, 0), row4(r, 1), row4(r, 2), min_q_, max_q_,
                   sensor_j_.height, sensor_j_.width, fov_up_rad, inv_row_step, col_tab_, row_tab_,
                   src_target_, src_key_, key_, out.status);
  launch_1d(zmin_k_, size_t(n_src_));
  winner_k_.set_args(n_src_, depth_i, src_target_, src_key_, key_, out.winner, out.status);
  launch_1d(winner_k_, size_t(n_src_));
  resolve_k_.set_args(n_dst_, key_, out.winner, out.range, out.mask);
  launch_1d(resolve_k_, size_t(n_dst_));
  return ctx;
}

void CrossFrameReprojection::check_status(const ReprojectionOutput& out) const {
  const auto s = out.status.read_vec<int>(2);
  if (s[0] == INT_MAX) return;
  float v;
  std::memcpy(&v, &s[1], sizeof v);
  throw NumericError("CrossFrameReprojection: depth_i at source pixel " + std::to_string(s[0]) +
                     " (row " + std::to_string(s[0] / sensor_i_.width) + ", col " +
                     std::to_string(s[0] % sensor_i_.width) + ") is " + num(v) +
                     "; depths must be finite and ≥ 0 (0 = no depth)");
}

ReprojectionImages CrossFrameReprojection::read(const ReprojectionOutput& out) const {
  check_output(out, "CrossFrameReprojection::read");
  check_status(out);
  return {out.range.read_vec<float>(size_t(n_dst_)), out.mask.read_vec<float>(size_t(n_dst_)),
          out.winner.read_vec<int>(size_t(n_dst_))};
}

ReprojectionPoseGradient CrossFrameReprojection::backward(
    const ReprojectionContext& ctx, const cl::Buffer& depth_i, const ReprojectionOutput& out,
    const cl::Buffer& grad_range, cl::Buffer& grad_depth_i, const Vec6& xi_i, const Vec6& xi_j) {
  const std::string what = "CrossFrameReprojection::backward";
  check_words(depth_i, size_t(n_src_), what + " depth_i");
  check_output(out, what);
  check_words(grad_range, size_t(n_dst_), what + " grad_range (dL/dD_ij, " +
                                              std::to_string(sensor_j_.height) + " x " +
                                              std::to_string(sensor_j_.width) + ")");
  check_words(grad_depth_i, size_t(n_src_), what + " grad_depth_i");
  if (!xi_i.allFinite() || !xi_j.allFinite())
    throw NumericError(what + ": pose corrections are not finite (xi_i " + num(xi_i.norm()) +
                       ", xi_j " + num(xi_j.norm()) + " in norm)");
  const auto& r = ctx.rows_lidarj_lidari;
  bwd_clear_k_.set_args(n_src_, grad_depth_i);
  launch_1d(bwd_clear_k_, size_t(n_src_));
  bwd_k_.set_args(n_dst_, bwd_chunk_, depth_i, dirs_i_, row4(r, 0), row4(r, 1), row4(r, 2),
                  out.winner, grad_range, grad_depth_i, partial_);
  bwd_k_.launch({size_t(bwd_groups_) * kBwdGroup}, {kBwdGroup});
  check_status(out);
  const auto part = partial_.read_vec<float>(size_t(bwd_groups_) * kPartials);
  // Σ g·m and Σ g·(x × m) over the winners (m: the range's direction in lidar i), in group order.
  Vec3 s_m = Vec3::Zero(), s_xm = Vec3::Zero();
  for (int g = 0; g < bwd_groups_; ++g)
    for (int k = 0; k < 3; ++k) {
      s_m[k] += double(part[size_t(kPartials * g + k)]);
      s_xm[k] += double(part[size_t(kPartials * g + 3 + k)]);
    }
  if (!s_m.allFinite() || !s_xm.allFinite())
    throw NumericError(what + ": pose gradient is not finite (grad_range holds non-finite values?)");
  // Right perturbations T·[Exp(ε)|η]: dr/dε_i = x × m, dr/dη_i = m, dr/dε_j = 0,
  // dr/dη_j = −n = −R_ji m. In ξ = (ω, u): ε = J_r(ω) δω, η = Exp(ω)ᵀ δu (se3.hpp), so
  // dL/dω = J_r(ω)ᵀ dL/dε and dL/du = Exp(ω) dL/dη.
  const Mat3 R_ji = ctx.T_lidarj_lidari.linear();
  ReprojectionPoseGradient g;
  g.xi_i.head<3>() = right_jacobian_so3(xi_i.head<3>()).transpose() * s_xm;
  g.xi_i.tail<3>() = exp_so3(xi_i.head<3>()) * s_m;
  g.xi_j.head<3>() = Vec3::Zero();
  g.xi_j.tail<3>() = -(exp_so3(xi_j.head<3>()) * (R_ji * s_m));
  return g;
}

}  // namespace sgnlf::render
