// make_geometric_stage (see geometric_stage.hpp).
#include "pipeline/train/geometric_stage.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "core/config.hpp"
#include "core/error.hpp"
#include "io/pose_graph_svg.hpp"
#include "pipeline/train/checkpoint.hpp"
#include "posegraph/annealed_run.hpp"
#include "posegraph/confidence_graph.hpp"
#include "posegraph/trajectory_check.hpp"
#include "core/log.hpp"

namespace sgnlf::pipeline {
namespace fs = std::filesystem;

namespace {

// The confidence graph in force: its edges (checkpointed) and the loss over them.
struct GraphState {
  std::vector<posegraph::Edge> edges;
  std::shared_ptr<const posegraph::GraphLoss> loss;
  long built_epoch = -1;
};

void write_graph_files(const std::string& run_dir, long epoch, const posegraph::ConfidenceGraph& g,
                       const std::vector<Pose>& T_world_lidar) {
  const fs::path dir = fs::path(run_dir) / "pose_graph";
  fs::create_directories(dir);
  char name[32];
  std::snprintf(name, sizeof name, "epoch_%05ld", epoch);
  Json j = posegraph::confidence_graph_json(g);
  j["epoch"] = epoch;
  write_json_file((dir / (std::string(name) + ".json")).string(), j);
  write_json_file((dir / "latest.json").string(), j);
  std::vector<io::SvgGraphEdge> edges;
  for (const auto& p : g.pairs)
    if (p.kept) edges.push_back({p.i, p.j, p.weight, p.sequential});
  io::write_pose_graph_svg((dir / (std::string(name) + ".svg")).string(),
                           "confidence-aware pose graph, epoch " + std::to_string(epoch),
                           T_world_lidar, edges);
}

}  // namespace

double geometric_tau_scale(double tau_scale, const Sensor& sensor) {
  if (tau_scale >= 0.0) return tau_scale;
  return sensor.name == "nuscenes" ? 0.5 : 0.3;
}

posegraph::FeatureProvider field_features(LidarNerfModel& model, const SceneNormalization& norm) {
  posegraph::FeatureProvider p;
  p.dim = model.encoder().width();
  p.parts = model.encoder().parts();  // f_geo and λΨ normalised on their own
  p.name = "field encoding (f_hyb with the hybrid field)";
  p.eval = [&model, norm](const std::vector<Eigen::Vector3f>& x_world, std::vector<float>& out) {
    std::vector<float> x(x_world.size() * 3);
    for (size_t k = 0; k < x_world.size(); ++k)
      for (int a = 0; a < 3; ++a)
        x[3 * k + size_t(a)] = float(std::clamp(
            (double(x_world[k][a]) - norm.center[a]) * norm.scale, -1.0, 1.0));
    out = model.encode_points(x, int(x_world.size()));
  };
  return p;
}

GeometricStage make_geometric_stage(const Dataset& d, const Scene& scene, const TrainConfig& c,
                                    posegraph::FeatureProvider features, std::string run_dir) {
  if (!c.geometric_stage()) return {};
  const GeometricScheduleConfig& g = *c.pose_free->geometric;
  const posegraph::GeometricConfig& gc = g.optimizer;
  std::vector<std::vector<PointXYZI>> scans;
  for (const auto& f : d.frames) scans.push_back(f.points);
  auto clouds = std::make_shared<const std::vector<posegraph::FrameCloud>>(
      gc.clouds(scans));
  auto loss = std::make_shared<const posegraph::GraphLoss>(
      clouds, posegraph::sequential_edges(int(d.frames.size()), gc.edge_offsets), gc.min_distance,
      gc.threads, gc.direction());
  // The re-seeding's judge, when it differs from the stage's residual (edge_reseeding.hpp).
  const auto judge = g.reseed ? posegraph::make_judge_loss(*loss, scans, gc, *g.reseed) : nullptr;
  // The fine registration after the coarse alignment (pose_free_config.hpp), its own clouds
  // and edges; released once it has run unless the later epochs keep its estimator.
  std::shared_ptr<std::shared_ptr<const posegraph::GraphLoss>> refine_loss;
  std::shared_ptr<const std::vector<posegraph::FrameCloud>> rclouds;
  const bool fine_later = g.refine && g.refine->later_epochs;
  if (g.refine) {
    const posegraph::GeometricConfig& rc = g.refine->optimizer;
    rclouds = std::make_shared<const std::vector<posegraph::FrameCloud>>(rc.clouds(scans));
    refine_loss = std::make_shared<std::shared_ptr<const posegraph::GraphLoss>>(
        std::make_shared<const posegraph::GraphLoss>(
            rclouds, posegraph::sequential_edges(int(d.frames.size()), rc.edge_offsets),
            rc.min_distance, rc.threads, rc.direction()));
  }
  // The later epochs' estimator: the refine's (residual, points, learning rates at lr·lr_final)
  // with later_epochs, else the schedule's own at lr·lr_final.
  const posegraph::GeometricConfig& later_cfg = fine_later ? g.refine->optimizer : gc;
  const double later_lr = fine_later ? g.refine->lr_final : g.lr_final;
  const auto later_clouds = fine_later ? rclouds : clouds;
  const SceneNormalization norm = scene.norm;
  const bool confidence = c.confidence_graph();
  if (confidence && !features.eval)
    throw Error("make_geometric_stage: the confidence pose graph needs a feature provider");
  const PoseGraphConfig pg = c.pose_graph.value_or(PoseGraphConfig{});
  auto graph = std::make_shared<GraphState>();

  GeometricStage stage;
  stage.run = [g, gc, loss, judge, refine_loss, norm, clouds, confidence, pg, graph, features,
               run_dir, fine_later, later_cfg, later_lr, later_clouds](PoseSet& poses, long epoch, double progress, const GeometricProgress& report) -> Json {
    const int steps = g.steps_at(epoch, progress);
    if (steps <= 0) return nullptr;
    auto tell = [&](long done, long total) {
      if (report) report(epoch, done, total);
    };
    // The steps of a run_annealed schedule after its k-th call, `offset` steps into the stage.
    auto after_call = [&](long offset, long total, const posegraph::AnnealConfig& a) {
      return [&, offset, total, a](int k, double, const posegraph::GeometricResult&) {
        tell(offset + std::min<long>(long(k) * a.per_call, a.steps), total);
      };
    };
    std::vector<Pose> T(poses.size());
    for (size_t i = 0; i < poses.size(); ++i) T[i] = denormalize_pose(poses.pose(i), norm);
    posegraph::GeometricResult r;
    Json graph_line, reseed_line, refine_line;
    if (epoch == 0) {  // the coarse alignment (sequential graph)
      log::info("coarse geometric alignment: ", steps, " steps over ", poses.size(),
                " scans before the first training step");
      posegraph::AnnealConfig a;
      a.steps = steps;
      a.per_call = g.per_call;
      a.lr_final = g.lr_final;
      tell(0, steps);
      const auto calls = posegraph::run_annealed(loss, gc, a, T, after_call(0, steps, a));
      r = calls.back();
      r.loss_before = calls.front().loss_before;
      r.steps = steps;
      if (g.reseed) {
        const auto rs = posegraph::reseed_edges(loss, gc, g.lr_final, *g.reseed, T, judge);
        log::info("edge re-seeding: ", rs.trials.size(), " hypotheses tried, ", rs.kept, " kept");
        reseed_line = posegraph::reseed_json(rs);
        std::vector<posegraph::PoseGrad> grad;
        r.loss_after = (*loss)(T, gc.tau_scale, grad);
      }
      if (g.refine && refine_loss && *refine_loss) {
        const GeometricRefineConfig& f = *g.refine;
        log::info("fine geometric registration: ", f.steps, " steps, ", f.optimizer.residual,
                  " over ", f.optimizer.edge_offsets.size(), " edge offsets");
        posegraph::AnnealConfig a;
        a.steps = f.steps;
        a.per_call = f.per_call;
        a.lr_final = f.lr_final;
        const std::vector<Pose> T_before = T;
        const auto calls = posegraph::run_annealed(*refine_loss, f.optimizer, a, T);
        double moved_m = 0.0, turned_rad = 0.0;  // the largest move of a frame
        for (size_t i = 0; i < T.size(); ++i) {
          const Pose d = T_before[i].inverse() * T[i];
          moved_m = std::max(moved_m, double(d.translation().norm()));
          turned_rad = std::max(turned_rad, double(Eigen::AngleAxisd(d.rotation()).angle()));
        }
        refine_line = Json{{"steps", f.steps},
                           {"residual", f.optimizer.residual},
                           {"loss_before", calls.front().loss_before},
                           {"loss_after", calls.back().loss_after},
                           {"max_frame_move_m", moved_m},
                           {"max_frame_turn_rad", turned_rad}};
        if (!fine_later) refine_loss->reset();
        std::vector<posegraph::PoseGrad> grad;
        r.loss_after = (*loss)(T, gc.tau_scale, grad);
      }
      tell(steps, steps);
    } else {  // the shrinking refinement at the final τ and learning rates
      long build_done = 0;  // the steps settling the poses on a new graph, before the refinement's
      if (confidence && epoch >= pg.start_epoch &&
          (graph->built_epoch < 0 || epoch - graph->built_epoch >= pg.graph.reevaluate_every)) {
        const auto cg = posegraph::build_confidence_graph(*clouds, T, features, pg.graph);
        graph->edges = cg.edges;
        graph->loss = std::make_shared<const posegraph::GraphLoss>(
            later_clouds, cg.edges, later_cfg.min_distance, later_cfg.threads,
            later_cfg.direction(), pg.graph.edge_max_distance_m);
        graph->built_epoch = epoch;
        if (!run_dir.empty()) write_graph_files(run_dir, epoch, cg, T);
        graph_line = Json{{"built", true},
                          {"edges", cg.edges.size()},
                          {"non_adjacent_edges", cg.non_adjacent_edges()},
                          {"threshold", std::isfinite(cg.threshold) ? Json(cg.threshold) : Json()}};
        const int build_steps = int(std::lround(
            pg.steps_on_build * std::max(0.0, 1.0 - progress / g.stop_progress)));
        if (build_steps > 0) {  // settle the poses on the new graph (pose_graph_config.hpp)
          posegraph::AnnealConfig a;
          a.steps = build_steps;
          a.per_call = g.per_call;
          // The fine estimator settles at its own final rates: its steps are already small.
          a.lr_start = fine_later ? later_lr : pg.lr_on_build;
          a.lr_final = later_lr;
          a.hold_clock = true;
          tell(0, build_steps + steps);
          const auto calls = posegraph::run_annealed(graph->loss, later_cfg, a, T,
                                                     after_call(0, build_steps + steps, a));
          build_done = build_steps;
          graph_line["build_run"] = Json{{"steps", build_steps},
                                         {"loss_before", calls.front().loss_before},
                                         {"loss_after", calls.back().loss_after}};
        }
      }
      posegraph::GeometricConfig run_cfg = later_cfg;
      run_cfg.steps = steps;
      run_cfg.lr_rotation *= later_lr;
      run_cfg.lr_translation *= later_lr;
      const auto& use = graph->loss ? graph->loss : fine_later ? *refine_loss : loss;
      const posegraph::GeometricOptimizer opt(posegraph::GraphLoss::as_pose_loss(use),
                                              poses.size(), run_cfg);
      tell(build_done, build_done + steps);
      r = opt.run(T, 1.0);
      tell(build_done + steps, build_done + steps);
      if (graph->loss && graph_line.is_null()) graph_line = Json{{"built", false}};
    }
    for (size_t i = 0; i < poses.size(); ++i) poses.set_pose(i, normalize_pose(T[i], norm));
    Json line{{"steps", r.steps},        {"tau", r.tau},
              {"loss_before", r.loss_before}, {"loss_after", r.loss_after},
              {"max_rotation_rad", r.max_rotation_rad},
              {"max_translation_m", r.max_translation_m}};
    if (epoch == 0) {  // did the coarse alignment register the scans? (no ground truth used)
      const auto chk = posegraph::check_trajectory(
          *clouds, T, posegraph::sequential_edges(int(T.size()), {1}));
      line["check"] = chk.to_json();
      if (!chk.converged)
        log::warn("the coarse geometric alignment did not converge: ", chk.reason);
    }
    if (epoch > 0 && fine_later) line["estimator"] = "refine";  // later_epochs (see above)
    if (!reseed_line.is_null()) line["reseed"] = reseed_line;
    if (!refine_line.is_null()) line["refine"] = refine_line;
    if (!graph_line.is_null()) {
      graph_line["edges_in_use"] = graph->edges.size();
      graph_line["graph_epoch"] = graph->built_epoch;
      line["pose_graph"] = graph_line;
    }
    return line;
  };
  if (confidence) {
    stage.state = [graph]() {
      std::vector<double> e;
      for (const auto& x : graph->edges) e.insert(e.end(), {double(x.i), double(x.j), x.weight});
      return NamedArrays{{"pose_graph.built_epoch", pack_doubles({double(graph->built_epoch)})},
                         {"pose_graph.edge_count", pack_doubles({double(graph->edges.size())})},
                         {"pose_graph.edges", pack_doubles(e)}};
    };
    stage.load_state = [graph, later_clouds, later_cfg, pg](const Checkpoint& ck) {
      graph->built_epoch = long(unpack_doubles(ck.array("pose_graph.built_epoch", 2)).at(0));
      const size_t n = size_t(unpack_doubles(ck.array("pose_graph.edge_count", 2)).at(0));
      const auto e = unpack_doubles(ck.array("pose_graph.edges", n == 0 ? 0 : 6 * n));
      graph->edges.clear();
      for (size_t k = 0; k < n; ++k)
        graph->edges.push_back({int(e[3 * k]), int(e[3 * k + 1]), e[3 * k + 2]});
      graph->loss.reset();
      if (!graph->edges.empty())
        graph->loss = std::make_shared<const posegraph::GraphLoss>(
            later_clouds, graph->edges, later_cfg.min_distance, later_cfg.threads,
            later_cfg.direction(), pg.graph.edge_max_distance_m);
    };
  }
  return stage;
}

}  // namespace sgnlf::pipeline
