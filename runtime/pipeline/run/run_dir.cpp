// Run folder manifest and loading (see run_dir.hpp).
#include "pipeline/run/run_dir.hpp"
#include "core/config.hpp"
#include "pipeline/train/spectral_schedule.hpp"

#include <filesystem>

#include "core/log.hpp"
#include "datasets/loader.hpp"
#include "datasets/protocol.hpp"
#include "pipeline/train/checkpoint.hpp"
#include "pipeline/train/pose_init.hpp"
#include "pipeline/train/pose_set.hpp"
#include "pipeline/train/trainer.hpp"

namespace sgnlf::pipeline {
namespace fs = std::filesystem;

void write_manifest(const std::string& run_dir, const RunManifest& m) {
  fs::create_directories(run_dir);
  Json j{{"method", m.method},   {"preset", m.preset}, {"dataset", m.dataset},
         {"device", m.device},   {"seed", m.seed},     {"config_hash", hex64(m.config.hash())},
         {"config", train_config_to_json(m.config)}};
  if (!m.data_options.is_default()) j["dataset_options"] = m.data_options.to_json();
  write_json_file((fs::path(run_dir) / "run.json").string(), j);
}

RunManifest read_manifest(const std::string& run_dir) {
  const std::string path = (fs::path(run_dir) / "run.json").string();
  if (!fs::exists(path)) throw IoError(path + ": not a run folder (no run.json)");
  const Json j = load_json_file(path);
  RunManifest m;
  ConfigReader r(j, path);
  std::string hash;
  Json cfg, data_options = Json::object();
  r.require("method", m.method).require("preset", m.preset).require("dataset", m.dataset);
  r.get("device", m.device).require("seed", m.seed).get("config_hash", hash).require("config", cfg);
  r.get("dataset_options", data_options);
  r.finish();
  m.data_options = LoadOptions::from_json(data_options, path + ": dataset_options");
  // Config shape 1 (before the modules' configs were embedded: field.levels, optim.beta1, …):
  // its checkpoints hold that config's hash, so the run cannot be read back as it is.
  if (cfg.is_object() && cfg.contains("field") && cfg["field"].is_object() &&
      cfg["field"].contains("levels"))
    throw ConfigError(path + ": this run was written by an older sgnlf (config shape 1: "
                      "'field.levels' where the hash grid is now 'field.grid'); train it again "
                      "with this version, or eval, render and resume it with the version that "
                      "wrote it");
  m.config = train_config_from_json(cfg, path + ": config");
  return m;
}

std::string run_sensor_path(const std::string& run_dir) {
  return (fs::path(run_dir) / "sensor.json").string();
}

LoadOptions run_load_options(const std::string& run_dir, const LoadOptions& opt) {
  LoadOptions o = opt;
  if (o.sensor.empty() && fs::is_regular_file(run_sensor_path(run_dir))) o.sensor = run_sensor_path(run_dir);
  return o;
}

void write_run_sensor(const std::string& run_dir, const Sensor& s) {
  if (s.name != "estimated") return;
  fs::create_directories(run_dir);
  write_json_file(run_sensor_path(run_dir), sensor_to_json(s));
}

RunScene make_run_scene(const Dataset& d, const TrainConfig& c) {
  if (!c.is_pose_free()) {
    if (!d.has_reference_poses)
      throw ConfigError("method " + c.method + " trains on known poses, and " + d.path +
                        " holds scans without them; use a pose-free method (sg-nlf, geonlf) "
                        "with --pose-init odometry, or sgnlf reconstruct");
    return RunScene{make_scene(d), gt_poses(d)};
  }
  if (d.split.test.empty())
    throw ConfigError("dataset " + d.name + ": " + std::to_string(d.frames.size()) +
                      " frames hold none of the protocol's test frames (4, 12, 20 of a 36-frame "
                      "low-frequency window); a pose-free run needs at least one test view");
  std::vector<Pose> init = initial_poses(d, c.pose_free->poses);
  return RunScene{make_pose_free_scene(d, init), std::move(init)};
}

LoadedRun load_run(cl::Runtime& rt, const std::string& run_dir,
                   const std::string& dataset_override, const RenderSampling& requested,
                   const LoadOptions* data_options) {
  LoadedRun run;
  run.manifest = read_manifest(run_dir);
  const uint64_t trained_hash = run.manifest.config.hash();
  // The config's eval sampling applies unless the caller overrides it.
  RenderSampling sampling = requested;
  const render::RenderConfig& rc = run.manifest.config.render;
  if (sampling.n_samples == 0) sampling.n_samples = rc.eval_samples;
  if (sampling.n_importance == -1) sampling.n_importance = rc.eval_importance;
  if (sampling.n_samples < 0 || sampling.n_importance < -1)
    throw ConfigError("render sampling override: samples " + std::to_string(sampling.n_samples) +
                      ", importance " + std::to_string(sampling.n_importance) +
                      " (samples >= 1, importance >= 0)");
  if (sampling.n_samples > 0) run.manifest.config.render.n_samples = sampling.n_samples;
  if (sampling.n_importance >= 0) run.manifest.config.render.n_importance = sampling.n_importance;
  if (!sampling.depth.empty()) {
    run.manifest.config.render.eval_depth = sampling.depth;
    run.manifest.config.render.validate("render depth override");
  }
  if (!sampling.out_of_range.empty()) {
    if (sampling.out_of_range != "drop" && sampling.out_of_range != "keep")
      throw ConfigError("out-of-range override: '" + sampling.out_of_range +
                        "' (expected \"drop\" or \"keep\")");
    run.manifest.config.render.eval_drop_out_of_range = sampling.out_of_range == "drop";
  }
  const std::string data = dataset_override.empty() ? run.manifest.dataset : dataset_override;
  if (data_options) run.manifest.data_options = *data_options;
  run.dataset = std::make_unique<Dataset>(
      load_dataset(data, run_load_options(run_dir, run.manifest.data_options)));
  RunScene rs = make_run_scene(*run.dataset, run.manifest.config);
  run.scene = std::make_unique<Scene>(std::move(rs.scene));
  run.T_world_lidar_init = rs.T_world_lidar_init;
  const TrainConfig& c = run.manifest.config;
  run.model = std::make_unique<LidarNerfModel>(rt, c, float(run.scene->norm.scale),
                                               model_capacity(c));
  const Checkpoint ck =
      load_latest_checkpoint(checkpoint_path(run_dir), trained_hash, run.manifest.seed);
  run.model->set_params(ck.array("params", run.model->n_params()));  // the optimiser's: training's
  restore_hybrid_encoder(*run.model, c, ck);
  run.step = ck.step;
  run.pose_free = c.is_pose_free();
  if (c.ray_drop_refinement()) {
    const std::string file = ray_drop_unet_path(run_dir);
    if (fs::exists(file)) {
      run.ray_drop = std::make_unique<RayDropStage>(rt, *c.lidar4d->refine);
      run.ray_drop->load(file);
    } else {
      log::warn(file, ": missing (the run did not finish, or trained before the ray-drop "
                "refinement existed); rendering without the ray-drop U-Net");
    }
  }
  run.T_world_lidar = run.T_world_lidar_init;
  if (run.pose_free) {
    PoseSet poses(run.scene->T_world_lidar, c.pose_free->pose_optim);
    poses.load_state([&](const std::string& name, size_t n) { return ck.array(name, n); });
    for (size_t i = 0; i < poses.size(); ++i)
      run.T_world_lidar[i] = denormalize_pose(poses.pose(i), run.scene->norm);
  }
  return run;
}

}  // namespace sgnlf::pipeline
