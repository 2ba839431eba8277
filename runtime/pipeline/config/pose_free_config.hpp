// Configuration of the pose-free methods (method.md §0 "Poses", §3; protocol §3): how the poses
// start, their own Adam, GeoNLF's selective reweighting, the coarse-to-fine level mask, and the
// geometric optimiser's schedule. Present in a TrainConfig only for pose-free methods, so the
// ground-truth-pose methods' configs (and their hashes) are unchanged.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "core/config_choices.hpp"
#include "core/config_fwd.hpp"
#include "posegraph/edge_reseeding.hpp"
#include "posegraph/geometric_optimizer.hpp"

namespace sgnlf::pipeline {

struct PoseInitConfig {
  std::string init = "noisy";  // "gt", "noisy" (protocol §3), "identity" or "odometry"
  uint64_t noise_seed = 1;
  double sigma_rot_rad = 0.151, sigma_trans_m = 2.0;
  template <class Self, class V>  // keys and ranges (core/config_fields.hpp)
  static void fields(Self& s, V& v) {
    v("init", s.init);  // one of the four: PoseFreeConfig::validate
    v("noise_seed", s.noise_seed);
    v("sigma_rot_rad", s.sigma_rot_rad, 0.0, 3.2);
    v("sigma_trans_m", s.sigma_trans_m, 0.0, 1e3);
  }
};

// Per-frame Adam on ξ = (ω, u) (method.md §0): lr decays exponentially to lr·final_factor;
// ×identity_lr_factor when the poses start at the identity. Translation lr in metres of the
// normalised scene (the peers optimise in the normalised frame).
struct PoseOptimConfig {
  bool optimize = true;        // false: the poses stay at their initial values (control row)
  // The photometric pose updates begin at this step (0: the published methods, from the first
  // step). From a good start (the odometry) a field still blurred moves the poses away
  // (docs/studies/odometry/pose_free_from_odometry.md); later steps see a fitted field.
  long start_step = 0;
  double lr_rot = 5e-3, lr_trans = 1e-3, final_factor = 0.01, identity_lr_factor = 6.0;
  double beta1 = 0.9, beta2 = 0.999, eps = 1e-8;
  double lr_scale(const std::string& init) const { return init == "identity" ? identity_lr_factor : 1.0; }
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("optimize", s.optimize);
    v("lr_rot", s.lr_rot, 0.0, 1.0);
    v("lr_trans", s.lr_trans, 0.0, 1.0);
    v("final_factor", s.final_factor, 1e-6, 1.0);
    v("identity_lr_factor", s.identity_lr_factor, 1e-3, 1e3);
    v("start_step", s.start_step, 0L, 1L << 40, config::omit_when(0L));  // added later
    v("beta1", s.beta1, 0.0, 0.999999);
    v("beta2", s.beta2, 0.0, 0.999999999);
    v("eps", s.eps, 1e-30, 1.0);
  }
};

// GeoNLF's selective reweighting (our reading of method.md §3): a per-frame moving average of
// the range loss; the `fraction` of frames with the highest average train the network with
// lr × `factor` (their poses are probably still wrong). On when the "reweight" section is present.
struct ReweightConfig {
  double fraction = 0.1, factor = 0.25, ema = 0.9;
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("fraction", s.fraction, 0.0, 1.0);
    v("factor", s.factor, 0.0, 1.0);
    v("ema", s.ema, 0.0, 0.999999);
  }
};

// The geometric optimiser before each epoch (method.md §3), a shrinking schedule: before the
// first epoch the coarse alignment, `first_steps` steps annealed as posegraph/annealed_run.hpp
// (τ ramping to optimizer.tau_scale, lr decaying to lr·lr_final, a fresh Adam every 10 steps);
// before each later epoch round(steps_per_epoch · (1 − progress / stop_progress)) steps (none
// after stop_progress) at the final τ and lr·lr_final, each call a fresh pose-only Adam. The
// optimiser's own config is embedded whole ("optimizer": posegraph::GeometricConfig, every key
// but the per-call steps: edge offsets, learning rates in radians and metres per step, τ scale,
// the robust weights' min_distance, each frame's point subsample and its seed, the direction
// term, the normals of point_to_plane, the worker threads). The presets' τ scale is 1.5,
// measured (README, "GeoNLF"); GeoNLF published 0.5 (nuScenes) / 0.3 (KITTI). On when the
// "geometric" section is present (and then the poses must be optimised).
// A fine registration after the coarse alignment (and its re-seeding), before the first
// training step: `steps` more annealed steps (τ ramping to optimizer.tau_scale, the learning
// rates decaying to lr·lr_final, a fresh Adam every per_call steps) with an optimiser of its
// own, e.g. point-to-plane residuals over more points and edges i+1 … i+8, the estimator that
// takes the odometry's poses to centimetres (docs/studies/odometry/pose_free_from_odometry.md).
// The coarse stage's point-to-point Chamfer is what converges from metres away; near the
// minimum its matches between scans 0.5 s apart are biased along the surfaces, which a
// point-to-plane residual is not. With later_epochs (the default) every later geometric step
// keeps this estimator too: the shrinking refinement before each epoch and the settling runs on
// each new confidence graph take its residual, points and learning rates (lr·lr_final), and the
// graph's loss is built over its clouds; without it they fall back to the schedule's own
// optimiser, whose biased point-to-point steps measurably walk the refined poses back
// (docs/studies/fine-registration). Not in GeoNLF or the paper; on when present. With
// geometric.first_steps 0 there is no first stage at all: neither the coarse alignment nor these
// `steps` run (a start that is already aligned, the odometry's), while later_epochs still hands
// the later epochs this estimator.
struct GeometricRefineConfig {
  int steps = 100;
  double lr_final = 1.0;
  int per_call = 10;
  bool later_epochs = true;
  posegraph::GeometricConfig optimizer = default_optimizer();
  // Point-to-plane over 16000 points a frame, edges i+1 … i+8, τ scale 4, 5e-4 rad / 5e-3 m
  // steps, two threads: the from_odometry start's measured settings.
  static posegraph::GeometricConfig default_optimizer();
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("steps", s.steps, 1, 1 << 20);
    v("lr_final", s.lr_final, 1e-6, 1.0);
    v("per_call", s.per_call, 1, 1 << 20, config::omit_when(10));
    v("later_epochs", s.later_epochs);
    v.section("optimizer", s.optimizer);
  }
};

struct GeometricScheduleConfig {
  int first_steps = 100;
  double steps_per_epoch = 10.0;
  double stop_progress = 0.6;
  double lr_final = 0.05;
  // Adam steps per call of the annealed runs (coarse alignment, settling on a new graph): a
  // fresh Adam each call (posegraph/annealed_run.hpp).
  int per_call = 10;
  posegraph::GeometricConfig optimizer = default_optimizer();
  // Edge re-seeding after the coarse alignment (posegraph/edge_reseeding.hpp; not in GeoNLF or
  // the paper): on when present.
  std::optional<posegraph::ReseedConfig> reseed;
  std::optional<GeometricRefineConfig> refine;  // after the coarse alignment: on when present
  int steps_at(long epoch, double progress) const;
  // The pipeline's defaults for the optimiser (the module's, with GeoNLF's learning rates
  // 1e-2 rad / 1e-1 m, 12000 points a frame and two threads).
  static posegraph::GeometricConfig default_optimizer();
  // Keys and ranges; the optimiser's rules are its validate()'s (PoseFreeConfig::validate).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("first_steps", s.first_steps, 0, 1 << 20);
    v("steps_per_epoch", s.steps_per_epoch, 0.0, 1e6);
    v("stop_progress", s.stop_progress, 0.0, 1.0);
    v("lr_final", s.lr_final, 1e-6, 1.0);
    v("per_call", s.per_call, 1, 1 << 20, config::omit_when(10));
    v.section("optimizer", s.optimizer);
    v.optional("reseed", s.reseed);
    v.optional("refine", s.refine);
  }
};

struct PoseFreeConfig {
  PoseInitConfig poses;
  PoseOptimConfig pose_optim;
  // Optional sections, on exactly when present in the JSON (GeoNLF's, so on in a default one).
  std::optional<ReweightConfig> reweight = ReweightConfig{};
  bool coarse_to_fine = true;  // BARF level mask over the hash-grid levels (method.md §3)
  std::optional<GeometricScheduleConfig> geometric = GeometricScheduleConfig{};
  // Its keys sit at the top of the training config.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.section("poses", s.poses);
    v.section("pose_optim", s.pose_optim);
    v.optional("reweight", s.reweight);
    v("coarse_to_fine", s.coarse_to_fine);
    v.optional("geometric", s.geometric);
  }

  void validate(const std::string& where) const;
  static PoseFreeConfig from_json(ConfigReader& r);  // reads its keys; errors name r.where()
  void to_json(Json& j) const;  // adds its sections to a config object
};

}  // namespace sgnlf::pipeline
