// Cross-frame reprojection for the adversarial consistency term (method.md §4.3): frame i's
// rendered range image → points in lidar i → lidar j (T_lidarj_lidari = T_world_lidar_j⁻¹ ·
// T_world_lidar_i) → frame j's range image, nearest point per pixel: D_ij, its mask M_ij and,
// per target pixel, the winning source pixel. The backward pass differentiates the range
// r = ||R x + t|| of each winner with respect to its depth and to both poses' corrections
// ξ = (ω, u) of T = T_init · [Exp(ω) | u] (method.md §0, the PoseSet parametrisation; the
// same dL/dξ as render::pose_gradient, so the two can be added); the discrete choice of the
// pixel is not differentiated.
//
// Units: depths in any unit (the training loop uses the normalised scene: metres · scale);
// range_scale = depth units per metre converts sensor j's range limits (metres).
// Conventions (protocol §1): depth 0 = no depth; points with range ≥ max or ≤ min range of
// sensor j, or outside its image, are dropped; the pixel follows the protocol's rounding
// (geometry/pixel_boundaries.hpp).
// Determinism: D_ij, M_ij and the winners are bit-identical from run to run, whatever the
// scheduling (ties in range go to the smallest source index), and the pixel choice is
// the same on every IEEE device; the gradients are summed in a fixed order (per work-group
// tree of a fixed size, then the groups in order in double on the host).
// Calls only enqueue, except backward() and read(), which wait for their results.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "cl/runtime.hpp"
#include "geometry/se3.hpp"
#include "geometry/sensor.hpp"

namespace sgnlf::render {

// One forward's results on the device, H_j × W_j each (make them with make_output()).
struct ReprojectionOutput {
  cl::Buffer range;   // D_ij: range in frame j (depth units), 0 where empty
  cl::Buffer mask;    // M_ij: 1 where a point landed, else 0 (floats)
  cl::Buffer winner;  // int32: source pixel index (row_i · W_i + col_i) in frame i, −1 = empty
  cl::Buffer status;  // 2 int32: smallest index of a bad depth (INT_MAX = none) and its bits
};

// What forward() used, for backward(): the poses and T_lidarj_lidari rounded to float as the
// kernels saw it (rows (R_k0, R_k1, R_k2, t_k), row-major).
struct ReprojectionContext {
  Pose T_world_lidar_i = Pose::Identity(), T_world_lidar_j = Pose::Identity();
  Pose T_lidarj_lidari = Pose::Identity();
  std::array<float, 12> rows_lidarj_lidari{};
};

// Host copy of a forward's results.
struct ReprojectionImages {
  std::vector<float> range, mask;
  std::vector<int> winner;
};

// dL/dξ of both frames in PoseSet's parametrisation, (dL/dω, dL/du). dL/dω_j is zero: a
// range measured from frame j's origin does not change when frame j turns about that origin
// (only the pixel it lands in would, and that choice is not differentiated).
struct ReprojectionPoseGradient {
  Vec6 xi_i = Vec6::Zero(), xi_j = Vec6::Zero();
};

// T_lidarj_lidari's rows rounded to float, as forward() passes them to the device.
std::array<float, 12> lidarj_lidari_rows(const Pose& T_lidarj_lidari);

// Throws NumericError for a non-finite pose and Error when `T` is not rigid (RᵀR ≠ I or
// det R ≤ 0 beyond 1e-6, or a bottom row other than 0 0 0 1), naming `what` and the deviation.
void check_rigid(const Pose& T, const std::string& what);

class CrossFrameReprojection {
 public:
  // sensor_i: frame i's image (the rendered depths, H_i × W_i); sensor_j: frame j's image and
  // range limits; range_scale > 0: depth units per metre.
  CrossFrameReprojection(cl::Runtime& rt, const Sensor& sensor_i, const Sensor& sensor_j,
                         double range_scale = 1.0);

  int source_pixels() const { return n_src_; }
  int target_pixels() const { return n_dst_; }
  // Buffers for one forward's results.
  ReprojectionOutput make_output() const;

  // depth_i: H_i × W_i floats (0 = no depth; a negative or non-finite depth is reported by
  // read() and backward() as a NumericError naming the pixel, and is otherwise skipped).
  ReprojectionContext forward(const cl::Buffer& depth_i, const Pose& T_world_lidar_i,
                              const Pose& T_world_lidar_j, ReprojectionOutput& out);

  // grad_range: dL/dD_ij (H_j × W_j floats); writes grad_depth_i (H_i × W_i floats, zero for
  // sources that won no pixel) and returns dL/dξ_i, dL/dξ_j at the corrections xi_i, xi_j of
  // the poses forward() used (only their rotation parts ω enter). Waits for the device.
  ReprojectionPoseGradient backward(const ReprojectionContext& ctx, const cl::Buffer& depth_i,
                                    const ReprojectionOutput& out, const cl::Buffer& grad_range,
                                    cl::Buffer& grad_depth_i, const Vec6& xi_i,
                                    const Vec6& xi_j);

  // Waits and reads D_ij, M_ij and the winners; throws NumericError for a bad depth.
  ReprojectionImages read(const ReprojectionOutput& out) const;

 private:
  void check_output(const ReprojectionOutput& out, const std::string& what) const;
  void check_status(const ReprojectionOutput& out) const;

  cl::Runtime& rt_;
  Sensor sensor_i_, sensor_j_;
  int n_src_, n_dst_, bwd_groups_, bwd_chunk_;
  float min_q_, max_q_;
  cl::Buffer dirs_i_, col_tab_, row_tab_;             // constant tables
  cl::Buffer key_, src_target_, src_key_, partial_;  // scratch
  cl::Kernel clear_k_, zmin_k_, winner_k_, resolve_k_, bwd_clear_k_, bwd_k_;
};

}  // namespace sgnlf::render
