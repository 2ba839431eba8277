// SG-NLF's spectral embedding Ψ trained on the scene being reconstructed (method.md §4.1), in
// pose-free training:
//  - SpectralLoss, a loss term of the model's step (loss_term.hpp) with a parameter group of its
//    own and the optimiser for it: at every `every`-th step, after the batch's backward, Ψ takes
//    one step of the term's Adam (lr cosine-decayed) on the spectral loss of a batch drawn from
//    the surface pool; it reports "spectral", out of the divergence check's total (Ψ's
//    objective is not the field's);
//  - SpectralSchedule, the StepPolicy around the pose-free step: before each epoch, after the
//    wrapped policy's epoch hook (the geometric stage may have moved the poses), the surface pool
//    is rebuilt from the observed points of the training frames under the current poses,
//    thinned to uniform area density with PCA normals and tangents
//    (spectral::surface_from_points); its schedule (StepPolicy::set_schedules) is λ(t) of the
//    fusion f_hyb = [f_geo, λ·Ψ], on the configured ramp (LidarNerfModel::set_fusion_weight).
// Checkpoints carry Ψ's parameters, its optimiser's state and the poses the pool was built
// from, so a resumed run rebuilds the same pool and stays bit-identical.
#pragma once
#include <functional>
#include <vector>

#include "field/adam.hpp"
#include "geometry/se3.hpp"
#include "pipeline/train/step_policy.hpp"
#include "pipeline/model/loss_term.hpp"
#include "spectral/surface.hpp"

namespace sgnlf::pipeline {

// The observed points the pool is built from: per entry a dataset frame and its points in its
// own LiDAR frame (metres), and the scene normalisation.
struct SurfacePoolSource {
  std::vector<int> frames;
  std::vector<std::vector<Eigen::Vector3f>> points_lidar;
  SceneNormalization norm;
};

// Current pose (normalised frame) of a dataset frame.
using PoseOf = std::function<Pose(int frame)>;

class SpectralLoss final : public LossTerm {
 public:
  // Ψ's optimiser: Adam over `psi_params` floats (field::Adam's defaults). Throws sgnlf::Error
  // when the source is empty or its sizes disagree.
  SpectralLoss(cl::Runtime& rt, size_t psi_params, const TrainConfig& cfg, SurfacePoolSource source,
               uint64_t seed);

  const char* name() const override { return "spectral"; }
  void take_own_step(OwnGroupStep& group) override;
  void report(LossReport& r, const std::vector<float>&) const override;

  // The pool of `epoch` from the source's frames at their poses T_norm (normalised frame, one
  // per source entry). Throws NumericError when too few points survive the thinning.
  void build_pool(long epoch, const std::vector<Pose>& T_norm);
  const std::vector<int>& frames() const { return source_.frames; }
  size_t pool_size() const { return pool_.size(); }
  double last_loss() const { return last_loss_; }
  double seconds() const { return seconds_; }  // pool builds + spectral steps, this process
  // Ψ's optimiser: its moments and step count ("spectral.psi.adam_m", "adam_v", "adam_t").
  NamedArrays optimizer_state() const;
  int64_t optimizer_steps() const { return psi_adam_.step(); }
  NamedArrays state() const;  // the pool's epoch and poses, the last loss
  // Both of the above from a checkpoint (IoError on sizes that are not Ψ's).
  void load_state(const Checkpoint& ck);

 private:
  const TrainConfig& cfg_;
  SurfacePoolSource source_;
  uint64_t seed_;
  std::vector<spectral::SurfacePoint> pool_;
  std::vector<Pose> pool_poses_;  // per source entry, normalised
  long pool_epoch_ = -1;
  double last_loss_ = 0.0, seconds_ = 0.0;
  size_t psi_params_;
  field::Adam psi_adam_;
};

class SpectralSchedule : public StepPolicy {
 public:
  // `model` must have the hybrid encoder; its Ψ state goes into the checkpoints.
  SpectralSchedule(StepPolicy& inner, SpectralLoss& loss, const LidarNerfModel& model,
                   const TrainConfig& cfg, PoseOf pose_of);

  void on_epoch(long epoch, long step) override;
  // λ(t) of `step` (the fusion ramp), after the wrapped policy's schedules.
  void set_schedules(LidarNerfModel& model, long step) override;
  void step(LidarNerfModel& model, FieldOptimizer& optim, uint64_t seed, long step,
            float lr) override;
  Json log_fields() override;
  std::string progress_text() override;
  NamedArrays state() const override;
  void load_state(const Checkpoint& ck, LidarNerfModel& model) override;

  size_t pool_size() const { return loss_.pool_size(); }
  double seconds() const { return loss_.seconds(); }
  double last_loss() const { return loss_.last_loss(); }

 private:
  StepPolicy& inner_;
  SpectralLoss& loss_;
  const LidarNerfModel& model_;
  const TrainConfig& cfg_;
  PoseOf pose_of_;
};

// A trained model's hybrid encoder from its checkpoint (evaluation, rendering): Ψ's parameters
// and λ of the last step taken. Does nothing when the config has no hybrid encoder.
void restore_hybrid_encoder(LidarNerfModel& model, const TrainConfig& cfg, const Checkpoint& ck);

// The pool source of a pose-free scene: `points_per_frame` points subsampled (fixed seed) from
// the scan of every training frame that is not pose-only.
SurfacePoolSource make_surface_pool_source(const Dataset& d, const Scene& scene,
                                           int points_per_frame, uint64_t seed);

}  // namespace sgnlf::pipeline
