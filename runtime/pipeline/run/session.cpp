// train_run / render_run / eval_run (see session.hpp).
#include "pipeline/run/session.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "core/config.hpp"
#include "core/log.hpp"
#include "core/progress.hpp"
#include "io/cloud_writers.hpp"
#include "datasets/loader.hpp"
#include "io/png_writer.hpp"
#include "io/range_array.hpp"
#include "pipeline/run/evaluate.hpp"
#include "pipeline/run/ray_drop_stage.hpp"
#include "pipeline/model/render_view.hpp"
#include "datasets/protocol.hpp"
#include "metrics/evaluate.hpp"
#include "metrics/pose_errors.hpp"
#include "pipeline/methods/registry.hpp"
#include "pipeline/train/pose_check.hpp"
#include "pipeline/train/step_parts.hpp"
#include "pipeline/train/trainer.hpp"
#include "pipeline/run/trajectory_files.hpp"

namespace sgnlf::pipeline {
namespace fs = std::filesystem;

namespace {

// Two pictures stacked with a gap of black rows.
io::RgbImage stack(const io::RgbImage& a, const io::RgbImage& b, int gap) {
  io::RgbImage out;
  out.width = std::max(a.width, b.width);
  out.height = a.height + gap + b.height;
  out.rgb.assign(size_t(out.width) * out.height * 3, 0);
  auto blit = [&](const io::RgbImage& img, int row0) {
    for (int r = 0; r < img.height; ++r)
      std::copy_n(&img.rgb[size_t(r) * img.width * 3], size_t(img.width) * 3,
                  &out.rgb[(size_t(row0 + r) * out.width) * 3]);
  };
  blit(a, 0);
  blit(b, a.height + gap);
  return out;
}

}  // namespace

Json pose_metrics_json(const std::vector<Pose>& est, const std::vector<Pose>& gt,
                       const Dataset& d) {
  Json j = metrics::pose_metrics(est, gt,
                                 d.planar_reference ? metrics::PoseReference::horizontal
                                                        : metrics::PoseReference::full_3d);
  j["frames"] = est.size();
  return j;
}

Json train_run(cl::Runtime& rt, const TrainRequest& req) {
  const auto t_load = std::chrono::steady_clock::now();
  const fs::path run(req.run_dir);
  if (fs::exists(run / "run.json")) {
    const RunManifest old = read_manifest(req.run_dir);
    if (old.config.hash() != req.manifest.config.hash() || old.seed != req.manifest.seed ||
        !(old.data_options == req.manifest.data_options))
      throw ConfigError((run / "run.json").string() +
                        ": the folder holds a run with another config, seed or dataset options; use a new --out");
  }
  // The dataset first: a bad path or option leaves no run folder behind.
  // A resumed run reuses the sensor it estimated (deterministic, but no need to redo it).
  const Dataset d = load_dataset(req.manifest.dataset, fs::exists(run / "run.json")
                                                           ? run_load_options(req.run_dir, req.manifest.data_options)
                                                           : req.manifest.data_options);
  write_manifest(req.run_dir, req.manifest);
  write_run_sensor(req.run_dir, d.sensor);
  const TrainConfig& c = req.manifest.config;
  const RunScene rs = make_run_scene(d, c);
  const Scene& scene = rs.scene;
  LidarNerfModel model(rt, c, float(scene.norm.scale), model_capacity(c));
  TrainOptions opt;
  opt.run_dir = req.run_dir;
  opt.seed = req.manifest.seed;
  opt.resume = req.resume;
  opt.stop_at = req.stop_at;
  opt.show_progress = req.show_progress;
  opt.on_progress = req.on_progress;
  // The method composes its step from the parts (methods/); a part whose feature the config
  // turns off is not built.
  RunStepParts parts(rt, d, scene, c, model, req.run_dir, req.manifest.seed);
  opt.policy = &find_method(c.method).compose(parts);
  PoseFreeStep* pose_step = parts.pose_step();
  if (pose_step && req.on_geometric_progress) pose_step->set_geometric_progress(req.on_geometric_progress);
  ConsistencySchedule* consistency_step = parts.consistency_step();
  SpectralSchedule* spectral_step = parts.spectral_step();
  auto current_poses = [&] { return pose_step ? pose_step->poses_world() : rs.T_world_lidar_init; };
  const double load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_load).count();
  opt.evaluate = [&](long) {
    Json m = evaluate_model(model, d, scene, c.schedule.render_chunk_rays, current_poses()).mean;
    if (pose_step && d.has_reference_poses) m["pose"] = pose_metrics_json(current_poses(), gt_poses(d), d);
    return m;
  };
  log::info("training ", c.method, "-", c.preset, " on ", d.name, " (", d.split.train.size(),
            " train / ", d.split.test.size(), " test frames, ", model.n_params(), " parameters, ",
            "device ", rt.device().describe(), ")");
  const TrainSummary s = train(model, scene, c, opt);
  Json j{{"dataset", d.name},
         {"train_frames", d.split.train.size()},
         {"test_frames", d.split.test.size()},
         {"parameters", model.n_params()},
         {"scene_scale", scene.norm.scale},
         {"start_step", s.start_step},
         {"end_step", s.end_step},
         {"finished", s.finished},
         {"train_seconds", s.seconds},
         {"load_seconds", load_s},
         {"steps_per_s", s.steps_per_s},
         {"samples_per_s", s.samples_per_s},
         {"live_fraction", s.live_fraction},
         {"first_loss", loss_json(s.first_loss)},
         {"last_loss", loss_json(s.last_loss)},
         {"device", rt.device().describe()}};
  if (!req.context.is_null()) j["context"] = req.context;
  if (pose_step) {
    if (d.has_reference_poses) {
      j["pose_metrics"] = pose_metrics_json(current_poses(), gt_poses(d), d);
      j["initial_pose_metrics"] = pose_metrics_json(rs.T_world_lidar_init, gt_poses(d), d);
    }
    j["geometric_seconds"] = pose_step->geometric_seconds();
    if (spectral_step) j["spectral_seconds"] = spectral_step->seconds();
    if (consistency_step) {
      j["consistency_seconds"] = consistency_step->seconds();
      j["consistency_steps"] = consistency_step->steps_taken();
    }
    j["trajectories"] = write_run_trajectories(req.run_dir, d, rs.T_world_lidar_init, current_poses());
    const posegraph::TrajectoryCheck chk = check_run_poses(d, current_poses());
    j["trajectory_check"] = chk.to_json();
    if (!chk.converged)
      log::warn(d.name, ": the poses did NOT converge (", chk.reason,
                "); the run's metrics describe a broken trajectory (summary.json trajectory_check)");
  }
  // LiDAR4D's ray-drop U-Net after the field (ray_drop_stage.hpp), once the run is finished.
  if (s.finished && c.ray_drop_refinement())
    j["ray_drop_refinement"] =
        refine_finished_run(rt, c, model, scene, d, current_poses(), req.run_dir);
  write_json_file((run / "summary.json").string(), j);
  return j;
}

Json render_run(LoadedRun& run, const std::string& out_dir, FastRenderer* fast,
                const std::vector<int>& frame_ids, BakedRenderer* baked) {
  const Dataset& d = *run.dataset;
  // (frame index, its place in the test split or -1) for every view asked for.
  std::vector<std::pair<int, int>> views;
  if (frame_ids.empty()) {
    for (size_t k = 0; k < d.split.test.size(); ++k) views.emplace_back(d.split.test[k], int(k));
  } else {
    for (int id : frame_ids) {
      const auto it = std::find_if(d.frames.begin(), d.frames.end(),
                                   [id](const Frame& f) { return f.id == id; });
      if (it == d.frames.end())
        throw ConfigError("render: frame " + std::to_string(id) + " is not in dataset " +
                          d.name + " (frame ids " + std::to_string(d.frames.front().id) + " to " +
                          std::to_string(d.frames.back().id) + ")");
      const int index = int(it - d.frames.begin());
      const auto t = std::find(d.split.test.begin(), d.split.test.end(), index);
      views.emplace_back(index, t == d.split.test.end() ? -1 : int(t - d.split.test.begin()));
    }
  }
  fs::create_directories(out_dir);
  Json files = Json::array();
  // One naive image per test frame, in split order; only when a test frame is among the views.
  const bool any_test =
      std::any_of(views.begin(), views.end(), [](const auto& v) { return v.second >= 0; });
  const ViewSet naive = any_test ? evaluate_naive(d) : ViewSet{};
  for (const auto& [index, test_k] : views) {
    const Frame& fr = d.frames[size_t(index)];
    const Pose& T = run.T_world_lidar[size_t(index)];
    DepthStats stats;
    RangeImage pred =
        fast    ? fast->render(T, index)
        : baked ? baked->render(T, *run.scene, &stats)
                : render_view(*run.model, *run.scene, T,
                              run.manifest.config.schedule.render_chunk_rays, index, nullptr,
                              &stats);
    if (run.ray_drop) run.ray_drop->apply(pred);
    const std::string stem = (fs::path(out_dir) / std::to_string(fr.id)).string();
    Json entry{{"frame", fr.id}, {"test", test_k >= 0}, {"png", stem + ".png"},
               {"pred", stem + "_pred.npy"}, {"gt", stem + "_gt.npy"}};
    if (!fast) {
      io::write_float_npy(stem + "_opacity.npy", pred.height, pred.width, stats.opacity);
      entry["opacity"] = stem + "_opacity.npy";
    }
    io::write_range_npy(stem + "_pred.npy", pred);
    io::write_range_npy(stem + "_gt.npy", fr.image);
    io::RangePictureOptions po;
    po.max_range_m = d.sensor.max_range_m;
    io::write_png(stem + ".png", stack(io::range_image_picture(masked_prediction(pred), po),
                                       io::range_image_picture(fr.image, po), 12));
    if (test_k >= 0) {
      io::write_range_npy(stem + "_naive.npy", naive.images[size_t(test_k)]);
      entry["naive"] = stem + "_naive.npy";
    }
    files.push_back(entry);
  }
  return files;
}

Json render_poses(LoadedRun& run, const std::vector<Pose>& T_world_lidar,
                  const std::string& out_dir, FastRenderer* fast, const Sensor* sensor,
                  BakedRenderer* baked) {
  if (T_world_lidar.empty()) throw ConfigError("render_poses: no poses to render");
  fs::create_directories(out_dir);
  const std::unique_ptr<Scene> other =
      sensor ? std::make_unique<Scene>(view_with_sensor(*run.scene, *sensor)) : nullptr;
  const Scene& view = other ? *other : *run.scene;
  io::RangePictureOptions po;
  po.max_range_m = view.sensor.max_range_m;
  Json files = Json::array();
  Progress progress("render", long(T_world_lidar.size()));
  for (size_t k = 0; k < T_world_lidar.size(); ++k) {
    const Eigen::Vector3d o = normalize_pose(T_world_lidar[k], run.scene->norm).translation();
    if (o.cwiseAbs().maxCoeff() > 1.0)
      log::warn("render_poses: pose ", k, " has its origin at (", o.x(), ", ", o.y(), ", ", o.z(),
                ") in the normalised scene, outside the trained box [-1, 1]^3");
    RangeImage pred =
        fast    ? fast->render(T_world_lidar[k], -1, &view)
        : baked ? baked->render(T_world_lidar[k], view)
                : render_view(*run.model, view, T_world_lidar[k],
                              run.manifest.config.schedule.render_chunk_rays);
    if (run.ray_drop) run.ray_drop->apply(pred);
    char name[32];
    std::snprintf(name, sizeof name, "pose_%04zu", k);
    const std::string stem = (fs::path(out_dir) / name).string();
    const RangeImage masked = masked_prediction(pred);
    io::write_range_npy(stem + ".npy", pred);
    io::write_png(stem + ".png", io::range_image_picture(masked, po));
    io::write_pcd(stem + ".pcd", unproject(view.sensor, masked));
    files.push_back(Json{{"pose", k}, {"npy", stem + ".npy"}, {"png", stem + ".png"},
                         {"pcd", stem + ".pcd"}, {"origin_normalised", {o.x(), o.y(), o.z()}}});
    progress.update(long(k) + 1);
  }
  progress.finish();
  return files;
}

Json eval_run(LoadedRun& run, const std::string& run_dir, FastRenderer* fast,
              TestViewImages* images, BakedRenderer* baked) {
  const auto t0 = std::chrono::steady_clock::now();
  const ViewSet model = evaluate_model(*run.model, *run.dataset, *run.scene,
                                       run.manifest.config.schedule.render_chunk_rays,
                                       run.T_world_lidar, fast, run.ray_drop.get(),
                                       fast ? nullptr : baked);
  const double render_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // Without reference poses the naive baseline moves the scans with the run's own poses.
  const ViewSet naive = run.dataset->has_reference_poses ? evaluate_naive(*run.dataset)
                                                         : evaluate_naive(*run.dataset, run.T_world_lidar);
  Json j{{"method", run.manifest.method},
         {"preset", run.manifest.preset},
         {"dataset", run.dataset->name},
         {"dataset_path", run.manifest.dataset},
         {"seed", run.manifest.seed},
         {"step", run.step},
         {"render_eval_seconds", render_s},
         {"render_sampling", {{"n_samples", run.manifest.config.render.n_samples},
                              {"n_importance", run.manifest.config.render.n_importance},
                              {"depth", run.manifest.config.render.eval_depth}}},
         {"metrics", model.mean},
         {"per_frame", model.per_frame},
         {"naive_baseline", {{"metrics", naive.mean}, {"per_frame", naive.per_frame}}},
         {"metric_definitions", metrics::definitions()}};
  j["reference_poses"] = run.dataset->has_reference_poses;
  j["ray_drop_refinement"] = run.ray_drop != nullptr;
  if (run.pose_free) {
    if (run.dataset->has_reference_poses) {
      const auto gt = gt_poses(*run.dataset);
      j["pose_metrics"] = pose_metrics_json(run.T_world_lidar, gt, *run.dataset);
      j["initial_pose_metrics"] = pose_metrics_json(run.T_world_lidar_init, gt, *run.dataset);
    }
    j["pose_init"] = run.manifest.config.pose_free->poses.init;
    const fs::path summary = fs::path(run_dir) / "summary.json";  // the training's own check
    if (fs::exists(summary)) {
      const Json sj = load_json_file(summary.string());
      if (sj.contains("trajectory_check")) j["trajectory_check"] = sj.at("trajectory_check");
    }
    // SG-NLF: the confidence-aware pose graph in force at the end of training.
    const fs::path graph = fs::path(run_dir) / "pose_graph" / "latest.json";
    if (fs::exists(graph)) {
      const Json gj = load_json_file(graph.string());
      j["pose_graph"] = Json{{"epoch", gj.value("epoch", -1)},
                             {"non_adjacent_edges", gj.value("non_adjacent_edges", 0)},
                             {"file", graph.string()}};
    }
  }
  if (fast) {
    const auto& c = fast->counts();
    const double rays = double(std::max(1L, c.rays));
    j["renderer"] = Json{{"name", "fast"},
                         {"config", fast->config().to_json()},
                         {"render_seconds", c.render_seconds},
                         {"grid_seconds", c.grid_seconds},
                         {"density_rows_per_ray", double(c.evaluated) / rays},
                         {"head_rows_per_ray", double(c.head_rows) / rays}};
    if (fast->config().layout == "march")
      j["renderer"]["density_rows_per_ray_by_kind"] =
          Json{{"coarse", double(c.march.coarse) / rays},
               {"fine", double(c.march.fine) / rays},
               {"outside_grid", double(c.march.outside) / rays},
               {"dropped_after_hit", double(c.march.dropped) / rays}};
  }
  if (baked && !fast) {
    const auto& c = baked->counts();
    const double s = c.render_seconds;
    j["renderer"] = Json{{"name", "baked"},
                         {"head", baked->head()},
                         {"head_seconds", c.head_seconds},
                         {"head_rows_per_ray", c.rays > 0 ? double(c.head_rows) / double(c.rays) : 0.0},
                         {"spread_ray_fraction", c.rays > 0 ? double(c.spread_rays) / double(c.rays) : 0.0},
                         {"scene", baked->scene().provenance},
                         {"scene_bytes", baked->scene().bytes()},
                         {"render_seconds", s},
                         {"frames_per_s", s > 0 ? double(c.frames) / s : 0.0},
                         {"rays_per_s", s > 0 ? double(c.rays) / s : 0.0}};
  }
  const char* name = fast ? "metrics-fast.json" : baked ? "metrics-baked.json" : "metrics.json";
  write_json_file((fs::path(run_dir) / name).string(), j);
  if (images) *images = TestViewImages{model.images, naive.images};
  return j;
}

}  // namespace sgnlf::pipeline
