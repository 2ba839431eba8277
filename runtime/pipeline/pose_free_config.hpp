// Configuration of the pose-free methods (method.md §0 "Poses", §3; protocol §3): how the poses
// start, their own Adam, GeoNLF's selective reweighting, the coarse-to-fine level mask, and the
// geometric optimiser's schedule. Present in a TrainConfig only for pose-free methods, so the
// ground-truth-pose methods' configs (and their hashes) are unchanged.
#pragma once
#include <string>
#include <vector>

#include "core/config.hpp"

namespace sgnlf::pipeline {

struct PoseInitConfig {
  std::string init = "noisy";  // "gt", "noisy" (protocol §3), "identity" or "odometry"
  uint64_t noise_seed = 1;
  double sigma_rot_rad = 0.151, sigma_trans_m = 2.0;
};

// Per-frame Adam on ξ = (ω, u) (method.md §0): lr decays exponentially to lr·final_factor;
// ×identity_lr_factor when the poses start at the identity. Translation lr in metres of the
// normalised scene (the peers optimise in the normalised frame).
struct PoseOptimConfig {
  bool optimize = true;        // false: the poses stay at their initial values (control row)
  // The photometric pose updates begin at this step (0: the published methods, from the first
  // step). From a good start (the odometry) a field still blurred moves the poses away
  // (results/odometry/pose_free_from_odometry.md); later steps see a fitted field.
  long start_step = 0;
  double lr_rot = 5e-3, lr_trans = 1e-3, final_factor = 0.01, identity_lr_factor = 6.0;
  double beta1 = 0.9, beta2 = 0.999, eps = 1e-8;
  double lr_scale(const std::string& init) const { return init == "identity" ? identity_lr_factor : 1.0; }
};

// GeoNLF's selective reweighting (our reading of method.md §3): a per-frame moving average of
// the range loss; the `fraction` of frames with the highest average train the network with
// lr × `factor` (their poses are probably still wrong).
struct ReweightConfig {
  bool enabled = true;
  double fraction = 0.1, factor = 0.25, ema = 0.9;
};

// The geometric optimiser before each epoch (method.md §3), a shrinking schedule: before the
// first epoch the coarse alignment, `first_steps` steps annealed as posegraph/annealed_run.hpp
// (τ ramping to tau_scale, lr decaying to lr·lr_final, a fresh Adam every 10 steps); before each
// later epoch round(steps_per_epoch · (1 − progress / stop_progress)) steps (none after
// stop_progress) at the final τ and lr·lr_final, each call a fresh pose-only Adam. Metres and
// radians. tau_scale < 0: GeoNLF's published 0.5 (nuScenes) / 0.3 (KITTI); the presets use 1.5,
// measured (README, "GeoNLF").
struct GeometricScheduleConfig {
  bool enabled = true;
  int points_per_frame = 12000;
  std::vector<int> edge_offsets = {1, 2};
  int first_steps = 100;
  double steps_per_epoch = 10.0;
  double stop_progress = 0.6;
  double tau_scale = -1.0;
  double lr_rot = 1e-2, lr_trans = 1e-1;  // radians / metres per step (Adam)
  double lr_final = 0.05;
  // Direction term of the graph loss: "point_to_point" (GeoNLF's robust Chamfer) or
  // "point_to_plane" (posegraph/point_to_plane.hpp).
  std::string residual = "point_to_point";
  // The stage's own draws (each frame's point subsample, posegraph::GeometricConfig::seed) and
  // its worker threads (the graph loss's direction terms; results identical for any count).
  // Written only when not these values, so configs from before the keys keep their hash; the
  // thread count is left out of the hash (TrainConfig::hash).
  uint64_t seed = 1;
  int threads = 2;
  int steps_at(long epoch, double progress) const;
};

struct PoseFreeConfig {
  PoseInitConfig poses;
  PoseOptimConfig pose_optim;
  ReweightConfig reweight;
  bool coarse_to_fine = true;  // BARF level mask over the hash-grid levels (method.md §3)
  GeometricScheduleConfig geometric;

  void validate(const std::string& where) const;
  static PoseFreeConfig from_json(ConfigReader& r);  // reads its keys; errors name r.where()
  void to_json(Json& j) const;  // adds its sections to a config object
};

}  // namespace sgnlf::pipeline
