// reconstruct (see reconstruct.hpp).
#include "workflow/reconstruct.hpp"

#include <chrono>
#include <cstdio>
#include <memory>
#include <filesystem>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/staged_progress.hpp"
#include "harness/context.hpp"
#include "datasets/protocol.hpp"
#include "io/cloud_writers.hpp"
#include "io/trajectory_io.hpp"
#include "io/trajectory_svg.hpp"
#include "metrics/evaluate.hpp"
#include "odometry/trajectory.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/methods/registry.hpp"
#include "pipeline/run/anatomy_run.hpp"
#include "pipeline/run/session.hpp"
#include "report/report.hpp"
#include "workflow/job_record.hpp"
#include "workflow/scene_cloud.hpp"

namespace sgnlf::workflow {
namespace fs = std::filesystem;

namespace {

// The progress line's stages: the record's (kReconstructStages) with the training's coarse
// geometric alignment ("align": the training's loading and its first geometric stage, before
// step 1; minutes on a few dozen scans) shown as a stage of its own.
enum Stage : size_t { kOdometry, kAlign, kTrain, kEvaluate, kAnatomy, kRender, kCloud, kReport };
const std::vector<std::string> kProgressStages{"odometry", "align", "train",  "evaluate",
                                               "anatomy",  "render", "cloud", "report"};

Json pose_errors_json(const std::vector<Pose>& est, const std::vector<Pose>& ref, const Dataset& d) {
  Json j = metrics::pose_metrics(est, ref, d.planar_reference ? metrics::PoseReference::horizontal
                                                              : metrics::PoseReference::detect);
  j["frames"] = est.size();
  return j;
}

// The reference poses of the loaded frames: the layout's, else the file's line per frame id
// (the scan's index in name order); empty when there are none.
std::vector<Pose> reference_poses(const Dataset& d, const std::string& file) {
  if (d.has_reference_poses) {
    if (!file.empty())
      log::warn("--reference-poses ", file, ": ", d.path, " has its own reference poses; using those");
    return gt_poses(d);
  }
  if (file.empty()) return {};
  const std::vector<Pose> all = io::read_kitti_poses(file);
  std::vector<Pose> ref;
  for (const auto& f : d.frames) {
    if (f.id < 0 || size_t(f.id) >= all.size())
      throw IoError(file + ": " + std::to_string(all.size()) + " poses, but scan " +
                    std::to_string(f.id) + " of " + d.path + " needs line " + std::to_string(f.id + 1));
    ref.push_back(all[size_t(f.id)]);
  }
  return ref;
}

// The training config: the preset, the odometry start (the preset's from_odometry keys), the
// user's overrides last.
pipeline::TrainConfig reconstruct_config(const ReconstructRequest& req) {
  const pipeline::Method& m = pipeline::find_method(req.method);
  if (!m.sections.pose_free || !m.implemented)
    throw ConfigError("reconstruct: method '" + req.method +
                      "' does not recover poses; use a pose-free method (sg-nlf, geonlf)");
  Json overrides = req.config.empty() ? Json::object() : load_config_file(req.config);
  if (overrides.contains("poses") && overrides.at("poses").contains("init") &&
      overrides.at("poses").at("init") != "odometry")
    throw ConfigError("--config " + req.config + ": poses.init is \"odometry\" in sgnlf reconstruct");
  overrides = pipeline::merge_config_json(Json{{"poses", {{"init", "odometry"}}}}, overrides);
  return pipeline::resolve_config(req.method, req.preset, overrides,
                                  req.config.empty() ? "reconstruct" : "--config " + req.config);
}

Json odometry_stage(const Dataset& d, const std::string& run_dir, const std::vector<Pose>& ref,
                    StagedProgress& progress) {
  std::vector<const std::vector<PointXYZI>*> scans;
  std::vector<double> stamps;
  for (const auto& f : d.frames) {
    scans.push_back(&f.points);
    stamps.push_back(f.timestamp_s);
  }
  // The training's start (pipeline/train/pose_init.cpp): the same default options.
  const odometry::OdometryConfig cfg;
  const auto res = odometry::estimate_trajectory(
      scans, stamps, cfg, d.sensor, [&](size_t k, const odometry::FrameResult&) {
        progress.update(long(k + 1), long(scans.size()));
      });
  const fs::path dir = fs::path(run_dir) / "odometry";
  fs::create_directories(dir);
  io::write_kitti_poses((dir / "odometry.kitti.txt").string(), res.T_world_lidar);
  io::write_tum_poses((dir / "odometry.tum.txt").string(), stamps, res.T_world_lidar);
  std::vector<io::SvgTrajectory> lines;
  std::vector<std::pair<int, int>> links;
  if (!ref.empty()) {
    const Pose T0_inv = ref.front().inverse();
    std::vector<Pose> ref0;
    for (const Pose& T : ref) ref0.push_back(T0_inv * T);
    lines.push_back({"reference (first pose at the identity)", "#2ca02c", ref0});
    links.push_back({0, 1});
  }
  lines.push_back({"odometry", "#d62728", res.T_world_lidar});
  io::write_trajectory_svg((dir / "top_view.svg").string(), "odometry: " + d.name, lines, links);
  Json frames = Json::array();
  for (size_t k = 0; k < res.frames.size(); ++k) {
    const auto& fr = res.frames[k];
    frames.push_back(Json{{"frame", d.frames[k].id}, {"ok", fr.ok()},
                          {"fitness", fr.registration.fitness}, {"rmse_m", fr.registration.rmse},
                          {"sigma_m", fr.sigma}, {"failure", fr.registration.failure}});
  }
  Json j{{"scans", res.frames.size()},
         {"seconds", res.seconds},
         {"scans_per_second", res.scans_per_second()},
         {"failed", res.failed},
         {"kitti", (dir / "odometry.kitti.txt").string()},
         {"tum", (dir / "odometry.tum.txt").string()}};
  if (!ref.empty()) j["pose_errors"] = pose_errors_json(res.T_world_lidar, ref, d);
  write_json_file((dir / "odometry.json").string(), Json{{"config", cfg.to_json()}, {"result", j}, {"frames", frames}});
  if (!res.failed.empty()) {
    const int k = res.failed.front();
    throw Error("reconstruct: " + std::to_string(res.failed.size()) + " of " +
                std::to_string(d.frames.size()) + " scans did not register, the first scan " +
                std::to_string(d.frames[size_t(k)].id) + ": " +
                res.frames[size_t(k)].registration.failure + " (" + (dir / "odometry.json").string() +
                " lists all)");
  }
  return j;
}

// Rendering cost of `views` held-out views from the training's throughput (samples per second
// with the backward pass: an upper bound for a forward-only render).
double render_estimate_s(const pipeline::TrainConfig& c, const Sensor& s, size_t views,
                         double train_samples_per_s) {
  if (train_samples_per_s <= 0.0) return -1.0;
  const int ns = c.render.eval_samples > 0 ? c.render.eval_samples : c.render.n_samples;
  const int ni = c.render.eval_importance >= 0 ? c.render.eval_importance : c.render.n_importance;
  return double(views) * double(s.height) * double(s.width) * double(ns + ni) / train_samples_per_s;
}

// The folder as an absolute, lexically normal path without a trailing separator, so that the
// same folder named another way ("scans/", "./scans", relative or absolute) is the same request.
std::string absolute_folder(const std::string& path) {
  fs::path p = fs::absolute(fs::path(path)).lexically_normal();
  if (!p.has_filename() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
  return p.string();
}

}  // namespace

Json ReconstructRequest::to_json() const {
  Json j{{"scans", absolute_folder(scans)},
         {"method", method},
         {"preset", preset},
         {"seed", seed},
         {"load_options", load.to_json()}};
  j["config"] = config.empty() ? Json(nullptr) : load_config_file(config);
  return j;
}

Json reconstruct(cl::Runtime& rt, const ReconstructRequest& req) {
  require(!req.scans.empty() && !req.run_dir.empty(), "reconstruct: scans and run folder are required");
  req.load.validate();
  const pipeline::TrainConfig cfg = reconstruct_config(req);  // bad configs fail before any work
  JobRecord record((fs::path(req.run_dir) / "reconstruct.json").string(), req.to_json());
  StagedProgress progress("reconstruct", kProgressStages);

  const Dataset d = load_dataset(req.scans, pipeline::run_load_options(req.run_dir, req.load));
  const std::vector<Pose> ref = reference_poses(d, req.reference_poses);
  progress.estimate(kCloud, 1.0 + 1e-6 * 0.5 * double(d.frames.size()) * 3e4);
  progress.estimate(kReport, 2.0);

  // 1. Odometry.
  if (!record.done("odometry")) {
    progress.begin(kOdometry);
    record.finish("odometry", odometry_stage(d, req.run_dir, ref, progress));
    progress.end();
  }

  // 2. Training (resumes from its checkpoint).
  pipeline::TrainRequest tr;
  tr.manifest.method = req.method;
  tr.manifest.preset = req.preset;
  tr.manifest.dataset = absolute_folder(req.scans);
  tr.manifest.device = req.device;
  tr.manifest.seed = req.seed;
  tr.manifest.data_options = req.load;
  tr.manifest.config = cfg;
  tr.run_dir = req.run_dir;
  tr.resume = true;
  tr.show_progress = false;
  const size_t views = d.split.test.size();
  const double samples_per_step =
      double(cfg.schedule.rays_per_batch) * double(cfg.render.n_samples + cfg.render.n_importance);
  if (!record.done("train")) {
    progress.begin(kAlign);
    // The coarse alignment's steps (epoch 0); the later epochs' geometric stages are part of
    // the training steps' time.
    tr.on_geometric_progress = [&](long epoch, long done, long total) {
      if (epoch == 0 && progress.current() == long(kAlign)) progress.update(done, total);
    };
    // Rendering estimates from the training's measured throughput (its stage's rate: from the
    // first logged step on, known after a few), refreshed as it runs.
    tr.on_progress = [&](long done, long end, const std::string& text) {
      if (progress.current() != long(kTrain)) {  // the first step: the alignment is over
        progress.end();
        progress.begin(kTrain);
      }
      progress.update(done, end, text);
      const double steps_per_s = progress.stage_units_per_s();
      if (steps_per_s > 0) {
        const double r = render_estimate_s(cfg, d.sensor, views, steps_per_s * samples_per_step);
        progress.estimate(kEvaluate, r);
        progress.estimate(kRender, r);
      }
    };
    tr.context = harness::context_block(&rt.device(), &rt.device_profile());  // the report's build row
    const Json summary = pipeline::train_run(rt, tr);
    record.finish("train", summary);
    progress.end();
  }
  const Json& train_summary = record.stage("train");
  {
    const double r = render_estimate_s(cfg, d.sensor, views, train_summary.value("samples_per_s", 0.0));
    if (!record.done("evaluate")) progress.estimate(kEvaluate, r);
    if (!record.done("render")) progress.estimate(kRender, r);
    // The anatomy renders only when the evaluation's views are not in memory (a resumed job).
    if (!record.done("anatomy"))
      progress.estimate(kAnatomy, record.done("evaluate") ? r : 2.0 + 0.5 * double(views));
  }

  // 3–5 share the loaded run.
  std::unique_ptr<pipeline::LoadedRun> run;
  auto loaded = [&]() -> pipeline::LoadedRun& {
    if (!run)
      run = std::make_unique<pipeline::LoadedRun>(
          pipeline::load_run(rt, req.run_dir, "", pipeline::RenderSampling{}, nullptr));
    return *run;
  };
  pipeline::TestViewImages scored;  // the evaluation's views, for the anatomy
  bool have_scored = false;
  if (!record.done("evaluate")) {
    progress.begin(kEvaluate);
    const auto t0 = std::chrono::steady_clock::now();
    const Json m = pipeline::eval_run(loaded(), req.run_dir, nullptr, &scored);
    have_scored = true;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    Json j{{"metrics", m.at("metrics")},
           {"naive_baseline", m.at("naive_baseline").at("metrics")},
           {"test_frames", m.at("per_frame").size()},
           {"seconds", s},
           {"file", (fs::path(req.run_dir) / "metrics.json").string()}};
    if (m.contains("trajectory_check")) j["trajectory_check"] = m.at("trajectory_check");
    record.finish("evaluate", j);
    progress.end();
    if (!record.done("render")) progress.estimate(kRender, s);
  }
  if (!record.done("anatomy")) {
    progress.begin(kAnatomy);
    const Json a = pipeline::anatomy_run(loaded(), req.run_dir, have_scored ? &scored : nullptr);
    const Json& mean = a.at("model").at("mean");
    record.finish("anatomy", Json{{"file", (fs::path(req.run_dir) / "anatomy.json").string()},
                                  {"pictures", a.at("pictures").size()},
                                  {"cd_pred_to_gt_false", mean.at("cd_pred_to_gt/cause/false")},
                                  {"cd_gt_to_pred_missed", mean.at("cd_gt_to_pred/cause/missed")},
                                  {"depth_mse_false", mean.at("depth_mse/cause/false")}});
    progress.end();
  }
  if (!record.done("render")) {
    progress.begin(kRender);
    pipeline::LoadedRun& r = loaded();
    pipeline::FastRenderer fast(rt, *r.model, *r.scene, render::FastRenderConfig{},
                                r.manifest.config.schedule.render_chunk_rays);
    const std::string dir = (fs::path(req.run_dir) / "renders").string();
    const Json files = pipeline::render_run(r, dir, &fast);
    record.finish("render", Json{{"folder", dir}, {"files", files.size()}});
    progress.end();
  }
  if (!record.done("cloud")) {
    progress.begin(kCloud);
    pipeline::LoadedRun& r = loaded();
    const std::vector<PointXYZI> cloud = scene_cloud(*r.dataset, r.T_world_lidar);
    const std::string ply = (fs::path(req.run_dir) / "scene.ply").string();
    const std::string pcd = (fs::path(req.run_dir) / "scene.pcd").string();
    io::write_ply(ply, cloud);
    io::write_pcd(pcd, cloud);
    record.finish("cloud", Json{{"points", cloud.size()}, {"ply", ply}, {"pcd", pcd},
                                {"frame", "world = the first scan's sensor frame (odometry start)"}});
    progress.end();
  }
  // Pose errors against the reference, when there is one; recorded before the report, which
  // shows them, and the report rewritten when they are (a later run that only adds
  // --reference-poses changes no other stage).
  if (!ref.empty()) {
    const fs::path traj = fs::path(req.run_dir) / "trajectories";
    const std::vector<Pose> odo = io::read_kitti_poses(record.stage("odometry").at("kitti").get<std::string>());
    const std::vector<Pose> opt = io::read_kitti_poses((traj / "optimised.kitti.txt").string());
    record.set("pose_errors", Json{{"odometry", pose_errors_json(odo, ref, d)},
                                   {"optimised", pose_errors_json(opt, ref, d)}});
  }
  if (!record.done("report") || !ref.empty()) {
    progress.begin(kReport);
    const std::string page = report::write_report(req.run_dir);
    record.finish("report", Json{{"file", page}});
    progress.end();
  }

  Json out = record.json();
  out["run_dir"] = req.run_dir;
  progress.finish(record.stage("report").at("file").get<std::string>());
  write_json_file(record.path(), out);
  return out;
}

}  // namespace sgnlf::workflow
