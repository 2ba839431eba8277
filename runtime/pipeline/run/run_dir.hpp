// The run folder of `sgnlf train/render/eval` (issue item 6):
//   <run>/run.json           method, preset, seed, dataset path, device, resolved config, hash
//   <run>/checkpoints/latest.ckpt, <run>/train_log.jsonl, <run>/eval_log.jsonl (trainer.hpp)
//   <run>/summary.json       training summary (steps, seconds, samples/s, losses, context)
//   <run>/metrics.json       `sgnlf eval`: per-frame and mean metrics, model and naive baseline
//   <run>/renders/           `sgnlf render` default output
//   <run>/sensor.json        the sensor estimated from plain scans (datasets/sensor_estimate.hpp),
//                            when train estimated one; eval/render load with it
//   <run>/ray_drop_unet.bin  LiDAR4D's ray-drop U-Net, trained after the field (ray_drop_stage.hpp)
#pragma once
#include <memory>
#include <string>

#include "cl/runtime.hpp"
#include "core/config_fwd.hpp"
#include "datasets/loader.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/model/scene.hpp"
#include "pipeline/config/train_config.hpp"
#include "pipeline/run/ray_drop_stage.hpp"

namespace sgnlf::pipeline {

struct RunManifest {
  std::string method = "lidar-nerf", preset, dataset, device;
  uint64_t seed = 1;
  TrainConfig config;
  // How `dataset` is loaded (window, sensor, test frames); in run.json as "dataset_options" only
  // when set, so run folders written before it existed still load. eval/render reuse it.
  LoadOptions data_options;
};

void write_manifest(const std::string& run_dir, const RunManifest& m);
RunManifest read_manifest(const std::string& run_dir);  // ConfigError/IoError naming the file

// <run>/sensor.json
std::string run_sensor_path(const std::string& run_dir);
// The options a run's dataset loads with: `opt`, naming the sensor the run folder recorded
// (run_sensor_path) when `opt` names none and the file exists.
LoadOptions run_load_options(const std::string& run_dir, const LoadOptions& opt);
// Records `s` in the run folder when it was estimated from the scans (name "estimated"), so
// eval and render project with the sensor the run trained on; other sensors are not written.
void write_run_sensor(const std::string& run_dir, const Sensor& s);

// The scene a run trains on: ground-truth poses, or for the pose-free methods the initial poses
// its config asks for (pose_init.hpp), which also set the normalisation (protocol §2).
struct RunScene {
  Scene scene;
  std::vector<Pose> T_world_lidar_init;  // per frame, metres (= ground truth for GT methods)
};
RunScene make_run_scene(const Dataset& d, const TrainConfig& c);

// A run loaded for rendering or evaluation: dataset, scene, the model from the checkpoint and
// the poses it was trained with (the pose provider of evaluation and rendering).
struct LoadedRun {
  RunManifest manifest;
  std::unique_ptr<Dataset> dataset;
  std::unique_ptr<Scene> scene;
  std::unique_ptr<LidarNerfModel> model;
  long step = 0;
  bool pose_free = false;
  std::vector<Pose> T_world_lidar;       // per frame, metres: ground truth, or the optimised poses
  std::vector<Pose> T_world_lidar_init;  // per frame, metres: the initial poses
  // LiDAR4D's ray-drop U-Net, which eval and render apply to every view: loaded when the config
  // enables the refinement and <run>/ray_drop_unet.bin exists (null otherwise).
  std::unique_ptr<RayDropStage> ray_drop;
};

// Sampling used when rendering a loaded run (a finer sampling than training's is allowed: the
// checkpoint does not depend on it). 0 keeps the trained value; n_importance 0 is itself a valid
// override, so "keep" is -1 there.
struct RenderSampling {
  int n_samples = 0;
  int n_importance = -1;
  std::string depth;  // "expected", "median" or "mix" (render.eval_depth); empty keeps the config's
  // "drop" or "keep" a rendered return the sensor cannot report (render.eval_drop_out_of_range);
  // empty keeps the config's
  std::string out_of_range;
};

// `dataset_override` replaces the manifest's dataset path when not empty. The checkpoint is
// checked against the run's config as trained; `sampling`, else the config's eval_samples /
// eval_importance (and `sampling.depth`, else eval_depth), then changes the model's render sampling (LoadedRun::manifest.config shows
// the sampling in use).
// `data_options`, when given, replaces the manifest's dataset options (eval --sensor/--frequency).
LoadedRun load_run(cl::Runtime& rt, const std::string& run_dir,
                   const std::string& dataset_override = "", const RenderSampling& sampling = {},
                   const LoadOptions* data_options = nullptr);

}  // namespace sgnlf::pipeline
