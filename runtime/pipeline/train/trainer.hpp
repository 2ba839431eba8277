// The training loop (issue item 4): per step one ray batch from one training frame
// (ray_batch.hpp), the exponential learning-rate decay (method.md §0), the loss read back every
// log_every steps (the only host sync besides checkpoints), NaN/divergence detection, periodic
// evaluation, atomic checkpoints and exact resume, progress on stderr (Progress: one line on a
// TTY, plain lines otherwise).
//
// Run folder: <run>/checkpoints/latest.ckpt (the last good state: written only after the loss
// of that step was read, finite, and every parameter is finite), <run>/train_log.jsonl (one
// JSON object per logged step), <run>/eval_log.jsonl (periodic evaluations).
#pragma once
#include <cstdint>
#include <functional>
#include <string>

#include "core/config.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/model/scene.hpp"
#include "pipeline/train/step_policy.hpp"
#include "pipeline/config/train_config.hpp"

namespace sgnlf::pipeline {

struct TrainOptions {
  std::string run_dir;        // required: checkpoints and logs go here
  uint64_t seed = 1;
  bool resume = true;         // continue from <run>/checkpoints/latest.ckpt when present
  long stop_at = -1;          // stop (with a checkpoint) after this step; −1 = run to the end
  bool show_progress = true;
  // When set, called with (done, end step, text) wherever the
  // progress line would be updated, so that a caller can show the steps in its own line
  // (sgnlf reconstruct: one line over the whole job); independent of show_progress.
  std::function<void(long, long, const std::string&)> on_progress;
  // Called every eval_every steps with the step; returns metrics JSON written to eval_log.jsonl.
  std::function<Json(long)> evaluate;
  // What a step does (hooks per step and per epoch); nullptr = GroundTruthPoseStep.
  StepPolicy* policy = nullptr;
};

struct TrainSummary {
  long start_step = 0;        // > 0 when resumed
  long end_step = 0;
  double seconds = 0.0;
  double steps_per_s = 0.0;
  double samples_per_s = 0.0;  // rays × (uniform + importance) per second
  // Mean fraction of those samples evaluated (< 1 with early ray termination).
  double live_fraction = 1.0;
  LossReport first_loss, last_loss;  // first and last logged losses of this run
  bool finished = false;      // reached config.schedule.iterations
};

std::string checkpoint_path(const std::string& run_dir);

// The loss terms' values as train_log.jsonl and summary.json write them: {"total", then each
// record by its name}.
Json loss_json(const LossReport& l);

// Trains `model` (initialised here from the seed unless a checkpoint is resumed).
// Throws NumericError on NaN/Inf or divergence, naming the step and the kept checkpoint.
TrainSummary train(LidarNerfModel& model, const Scene& scene, const TrainConfig& cfg,
                   const TrainOptions& opt);

}  // namespace sgnlf::pipeline
