// The pose-free training step (method.md §0 "Poses", §3): rays of a frame start from its
// current pose estimate; the backward pass reaches the frame's correction ξ through the ray
// origins and directions (render::pose_gradient) and the frame's own Adam moves it; test frames
// (scene.pose_only) train their pose only (network lr 0); GeoNLF's selective reweighting lowers
// the network lr of the frames with the highest recent loss; the coarse-to-fine level mask
// follows training progress; before each epoch a geometric stage (the GeoNLF graph optimiser,
// geometric_stage.hpp) may move the poses. Pose errors against ground truth (metres, protocol §4)
// go into train_log.jsonl and the progress line; each geometric stage's before/after ATE into
// <run>/geometric_log.jsonl.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "metrics/evaluate.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "pipeline/train/pose_grad_reader.hpp"
#include "pipeline/train/pose_set.hpp"
#include "pipeline/train/step_policy.hpp"

namespace sgnlf::pipeline {

// Called as a geometric stage runs: `done` of its `total` optimiser steps before epoch `epoch`
// (0 of them when it starts, total when it ends), e.g. for a progress line.
using GeometricProgress = std::function<void(long epoch, long done, long total)>;

// A geometric stage: `run` moves `poses` (normalised frame) before epoch `epoch` at `progress`,
// reporting its steps to `report` (may be empty), and returns a JSON summary (steps, losses)
// for the log, or null when it did nothing. A stage with state of its own (SG-NLF's current
// pose graph) saves it with the step's checkpoint arrays.
struct GeometricStage {
  std::function<Json(PoseSet& poses, long epoch, double progress, const GeometricProgress& report)> run;
  std::function<NamedArrays()> state;                  // optional
  std::function<void(const Checkpoint&)> load_state;  // optional
  explicit operator bool() const { return bool(run); }
};

class PoseFreeStep : public StepPolicy {
 public:
  // `T_world_lidar_gt` (metres, one per frame) for pose errors; may be empty (none reported).
  PoseFreeStep(const Scene& scene, const TrainConfig& cfg, PoseSet& poses,
               std::vector<Pose> T_world_lidar_gt, std::string run_dir,
               GeometricStage geometric = {});

  void on_epoch(long epoch, long step) override;
  // The coarse-to-fine level mask of `step` (BARF, pose_free.coarse_to_fine).
  void set_schedules(LidarNerfModel& model, long step) override;
  void step(LidarNerfModel& model, FieldOptimizer& optim, uint64_t seed, long step,
            float lr) override;
  Json log_fields() override;
  std::string progress_text() override;
  NamedArrays state() const override;
  void load_state(const Checkpoint& ck, LidarNerfModel& model) override;

  // Current poses in the dataset's world frame (metres).
  std::vector<Pose> poses_world() const;
  // Where the geometric stage reports its steps (none by default).
  void set_geometric_progress(GeometricProgress report) { report_ = std::move(report); }
  // Wall time spent in the geometric stage by this process (not across a resume).
  double geometric_seconds() const { return geometric_seconds_; }
  // Network lr multiplier of `frame` under selective reweighting (1 when off or not yet known).
  double reweight(int frame) const;
  // Which ATE the reference supports (Dataset::planar_reference): horizontal for nuScenes.
  void set_pose_reference(metrics::PoseReference r) { reference_ = r; }

 private:
  Json pose_errors() const;
  const Scene& scene_;
  const TrainConfig& cfg_;
  PoseSet& poses_;
  std::vector<Pose> gt_;
  metrics::PoseReference reference_ = metrics::PoseReference::full_3d;
  std::string run_dir_;
  GeometricStage geometric_;
  GeometricProgress report_;
  std::vector<double> ema_;   // per frame: moving average of the range loss
  std::vector<double> seen_;  // per frame: 1 once a step came from it
  std::vector<float> level_w_;
  double geometric_seconds_ = 0.0;
  // The device profile's pose_grad, chosen on the first step.
  std::unique_ptr<PoseGradReader> grad_reader_;
};

}  // namespace sgnlf::pipeline
