// SG-NLF's spectral embedding trained on the scene being reconstructed (method.md §4.1), as a
// StepPolicy that wraps another (the pose-free step): before each epoch, after the wrapped
// policy's epoch hook (the geometric stage may have moved the poses), the surface pool is
// rebuilt from the observed points of the training frames under the current poses, thinned to
// uniform area density with PCA normals and tangents (spectral::surface_from_points); at every
// `every`-th step Ψ takes one spectral step on a batch drawn from the pool (its own Adam, lr
// cosine-decayed), and λ(t) of the fusion f_hyb = [f_geo, λ·Ψ] follows the configured ramp.
// Checkpoints carry Ψ's parameters and Adam state and the poses the pool was built from, so a
// resumed run rebuilds the same pool and stays bit-identical.
#pragma once
#include <functional>
#include <vector>

#include "geometry/se3.hpp"
#include "pipeline/train/step_policy.hpp"
#include "spectral/hybrid_encoder.hpp"

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

class SpectralSchedule : public StepPolicy {
 public:
  // Throws sgnlf::Error when the source is empty or its sizes disagree.
  SpectralSchedule(StepPolicy& inner, spectral::HybridEncoder& encoder, const TrainConfig& cfg,
                   SurfacePoolSource source, PoseOf pose_of, uint64_t seed);

  void on_epoch(long epoch, long step) override;
  void step(LidarNerfModel& model, uint64_t seed, long step, float lr) override;
  Json log_fields() override;
  std::string progress_text() override;
  NamedArrays state() const override;
  void load_state(const Checkpoint& ck, LidarNerfModel& model) override;

  size_t pool_size() const { return pool_.size(); }
  double seconds() const { return seconds_; }  // pool builds + spectral steps, this process
  double last_loss() const { return last_loss_; }

 private:
  void build_pool(long epoch, const std::vector<Pose>& T_norm);

  StepPolicy& inner_;
  spectral::HybridEncoder& encoder_;
  const TrainConfig& cfg_;
  SurfacePoolSource source_;
  PoseOf pose_of_;
  uint64_t seed_;
  std::vector<spectral::SurfacePoint> pool_;
  std::vector<Pose> pool_poses_;  // per source entry, normalised
  long pool_epoch_ = -1;
  double last_loss_ = 0.0, seconds_ = 0.0;
};

// A trained model's hybrid encoder from its checkpoint (evaluation, rendering): Ψ's parameters
// and λ of the last step taken. Does nothing when the config has no hybrid encoder.
void restore_hybrid_encoder(LidarNerfModel& model, const TrainConfig& cfg, const Checkpoint& ck);

// The pool source of a pose-free scene: `points_per_frame` points subsampled (fixed seed) from
// the scan of every training frame that is not pose-only.
SurfacePoolSource make_surface_pool_source(const Dataset& d, const Scene& scene,
                                           int points_per_frame, uint64_t seed);

}  // namespace sgnlf::pipeline
