// The three run-level operations behind `sgnlf train/render/eval` and run_method(): train a run
// folder (new or resumed), render its test frames beside the ground truth, and evaluate it
// (with the naive baseline alongside).
#pragma once
#include <functional>
#include <string>

#include "cl/runtime.hpp"
#include "core/config.hpp"
#include "pipeline/model/baked_renderer.hpp"
#include "pipeline/model/fast_renderer.hpp"
#include "pipeline/run/anatomy_run.hpp"
#include "pipeline/run/run_dir.hpp"
#include "pipeline/train/pose_free_step.hpp"
#include "pipeline/train/trainer.hpp"

namespace sgnlf::pipeline {

struct TrainRequest {
  RunManifest manifest;       // method, preset, dataset, seed, device, resolved config
  std::string run_dir;
  bool resume = true;
  long stop_at = -1;
  bool show_progress = true;
  // Passed to TrainOptions::on_progress (done, end step, text).
  std::function<void(long, long, const std::string&)> on_progress;
  // Given to a pose-free method's geometric stage (PoseFreeStep::set_geometric_progress): its
  // optimiser steps (epoch, done, total) as it runs, the coarse alignment before the first
  // training step among them.
  GeometricProgress on_geometric_progress;
  // Where the training runs (git, build, machine, device: harness::context_block, which the
  // command fills in); written into summary.json as "context" when not null.
  Json context = nullptr;
};

// Writes run.json (or checks that an existing one has the same config and seed), trains, and
// writes summary.json. Returns the summary as JSON. A finished run whose config enables
// lidar4d.refine then trains (or, resumed, reloads) its ray-drop U-Net (ray_drop_stage.hpp):
// summary.json "ray_drop_refinement". render_run, render_poses and eval_run apply the U-Net a
// LoadedRun holds to every view (metrics.json "ray_drop_refinement": whether it did).
Json train_run(cl::Runtime& rt, const TrainRequest& req);

// Renders every test frame: <out>/<frame>_pred.npy, <frame>_gt.npy, <frame>_naive.npy (the naive
// baseline's view; H×W×3, io/range_array.hpp) and <frame>.png (rendered above ground truth: depth, intensity, mask). Returns the files.
// With `fast`, the views go through the fast renderer (pipeline::FastRenderer) instead of the
// protocol's. With `frame_ids` (the dataset's frame ids, training or test frames), those frames
// instead, at the run's poses and times; a test frame among them gets its naive view too, a
// training frame none (it is its own nearest scan). ConfigError names an id the dataset lacks.
// With `baked` (and no `fast`), the views are ray-cast from a baked scene (docs/baking.md).
// The protocol's and the baked renderer also write <frame>_opacity.npy (H×W: Σw along each ray,
// before the ray-drop refinement), which tells a missed return of a translucent field from one
// of a low return probability; the fast renderer does not.
Json render_run(LoadedRun& run, const std::string& out_dir, FastRenderer* fast = nullptr,
                const std::vector<int>& frame_ids = {}, BakedRenderer* baked = nullptr);

// Renders novel views at the given poses (T_world_lidar in the dataset's world frame, metres):
// <out>/pose_<k>.npy (H×W×3: range, return probability, intensity) and pose_<k>.png (the
// prediction masked at probability 0.5: depth, intensity, mask). ConfigError for an empty list;
// a pose whose origin lies outside the scene's normalised box is rendered with a warning (the
// field is only trained inside it). Returns the files with each pose's normalised origin.
// Also <out>/pose_<k>.pcd: the returns (probability > 0.5) as points in the sensor frame.
// One progress line over the poses. With `sensor`, the views are that sensor's (rows, field of
// view, resolution, range), not the recording one's.
Json render_poses(LoadedRun& run, const std::vector<Pose>& T_world_lidar,
                  const std::string& out_dir, FastRenderer* fast = nullptr,
                  const Sensor* sensor = nullptr, BakedRenderer* baked = nullptr);

// ATE (3D and horizontal, ate_reference), RPE_t, RPE_r (protocol §4, SE(3) Umeyama alignment;
// metrics::pose_metrics) of `est` against `gt`, as JSON, with "frames".
// Pose metrics of `est` against `d`'s reference poses `gt`, with the ATE the reference supports
// by d's source (nuScenes: horizontal; every other source: 3D).
Json pose_metrics_json(const std::vector<Pose>& est, const std::vector<Pose>& gt,
                       const Dataset& d);

// Per-frame and mean metrics of the model and of the naive baseline (pose-free runs: with the
// pose metrics of the optimised and the initial poses over all frames); writes <run>/metrics.json.
// With `fast`, the test views go through the fast renderer and the result (with the renderer's
// counts and config under "renderer") goes to <run>/metrics-fast.json: metrics.json stays the
// protocol's. With `images`, the scored views are left there (for anatomy_run, which then
// renders nothing again). With `baked` (and no `fast`), the views are ray-cast from a baked
// scene and the result (with the ray caster's counts under "renderer") goes to
// <run>/metrics-baked.json.
Json eval_run(LoadedRun& run, const std::string& run_dir, FastRenderer* fast = nullptr,
              TestViewImages* images = nullptr, BakedRenderer* baked = nullptr);

}  // namespace sgnlf::pipeline
