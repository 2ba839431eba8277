// SG-NLF's adversarial cross-frame consistency for one adjacent pair (i, j) (method.md §4.3):
// frame i's range image rendered from the field at its current pose on a sub-sampled sensor
// (depths whose predicted return probability is ≤ return_threshold set to 0: no point) →
// reprojected into frame j's image sub-sensor (render::CrossFrameReprojection, z-buffer) → D_ij
// and M_ij; fake = [D_ij, D_j], real = [M_ij ⊙ D_j, D_j] with D_j frame j's observed range
// image (metres); optionally one discriminator step (hinge L_D, its own Adam); then the
// generator term L_con = −mean D(fake) and its gradient, chained through the reprojection to
// frame i's depths (→ the field: the FieldPass's backward of the rays it rendered, into this
// training step's gradient) and to both poses' corrections ξ_i, ξ_j, all scaled by λ_con.
// One concept: the term and its gradient. When it runs and what the poses do with its
// gradient is the schedule's business (consistency_schedule.hpp).
#pragma once
#include <memory>
#include <vector>

#include "adversarial/patch_discriminator.hpp"
#include "pipeline/config/consistency_config.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/model/scene.hpp"
#include "render/cross_frame_reprojection.hpp"

namespace sgnlf::pipeline {

// The pair and both frames' poses (normalised frame) as T = T_init · [Exp(ξ_ω) | ξ_u].
struct ConsistencyPair {
  int i = 0, j = 0;  // dataset frames: i rendered, j observed
  Pose T_init_i = Pose::Identity(), T_init_j = Pose::Identity();
  Vec6 xi_i = Vec6::Zero(), xi_j = Vec6::Zero();
};

struct ConsistencyResult {
  // λ_con · dL_con/dξ of both frames (PoseSet's parametrisation): frame i through its rendered
  // depths (ray origins and directions) and the reprojection; frame j through the
  // reprojection only (its rotation gets none, render/cross_frame_reprojection.hpp).
  Vec6 grad_xi_i = Vec6::Zero(), grad_xi_j = Vec6::Zero();
  double l_con = 0.0;        // L_con = −mean D(fake) after the discriminator step, unweighted
  double l_d = 0.0;          // hinge L_D of the discriminator step (0 without one)
  double d_real_mean = 0.0;  // mean logit on real / fake in that step (before its update),
  double d_fake_mean = 0.0;  // averaged over scales (0 without a step)
  double coverage = 0.0;     // fraction of frame j's image pixels that M_ij covers
  int rendered_points = 0;   // frame i's pixels kept by the return threshold
};

class ConsistencyTerm {
 public:
  // Throws ConfigError when the sub-sensors do not fit the scene's sensor, the render grid
  // exceeds `max_rays` or the discriminator cannot run on the image sub-sensor.
  ConsistencyTerm(cl::Runtime& rt, const Scene& scene, const ConsistencyConfig& cfg,
                  int max_rays);

  // Renders frame i through `field` (jitter from its seed and step), reprojects, steps the
  // discriminator when `train_discriminator`, and writes the field's share of λ_con·dL_con
  // through the rendered rays' backward into the step's gradient. Pose gradients are computed
  // when `pose_grads` (else zero). Blocking (small read-backs).
  ConsistencyResult run(FieldPass& field, const ConsistencyPair& p, bool train_discriminator,
                        bool pose_grads);

  adversarial::PatchDiscriminator& discriminator() { return *disc_; }
  const Sensor& render_sensor() const { return sensor_i_; }
  const Sensor& image_sensor() const { return sensor_j_; }
  // Frame f's observed range image on the image sub-sensor, metres (0 = no return).
  const std::vector<float>& observed(int f) const { return observed_m_.at(size_t(f)); }
  // D_ij, M_ij and the winners of the last run() (host copies).
  const render::ReprojectionImages& last_reprojection() const { return last_img_; }

 private:
  ConsistencyConfig cfg_;
  Sensor sensor_i_, sensor_j_;
  double scale_;                   // normalised depth units per metre
  std::vector<float> dirs_i_;      // render sub-sensor directions (lidar frame), n_i × 3
  std::vector<std::vector<float>> observed_m_;
  std::unique_ptr<render::CrossFrameReprojection> reproj_;
  render::ReprojectionOutput out_;
  render::ReprojectionImages last_img_;
  std::unique_ptr<adversarial::PatchDiscriminator> disc_;
  cl::Buffer depth_i_, grad_depth_i_, grad_range_, real_m_, fake_m_, d_fake_m_;
};

}  // namespace sgnlf::pipeline
