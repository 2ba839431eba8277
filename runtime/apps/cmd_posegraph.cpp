// `sgnlf posegraph --data <dataset> [--pose-init noisy|identity|gt] [--steps N] [--points N]
// [--tau-scale X] [--lr-rot X] [--lr-trans X] [--lr-final X] [--offsets 1,2] [--out DIR]
// [--graph sequential|confidence] [--graph-config FILE] [--confidence-start X] [--sensor NAME|FILE]
// [--frequency standard|low|HZ]`:
// GeoNLF's geometric pose optimiser alone (no field; method.md §3) from the protocol's initial
// poses, as the coarse alignment that starts a GeoNLF run (posegraph/annealed_run.hpp). Prints the ATE/RPE after each call; with --out writes
// the trajectories (pipeline/run/trajectory_files.hpp) and a JSON log.
// --graph confidence: SG-NLF's confidence-aware pose graph (method.md §4.2) with the STAND-IN
// features (posegraph/standin_features.hpp, not the field's f_hyb) on the staged schedule of
// posegraph/staged_graph_run.hpp; --out adds graphs/graph_after_call_<k>.{json,svg} for every
// (re-)evaluation.
#include <cmath>
#include <cstdio>
#include <memory>
#include <filesystem>
#include <iostream>

#include "apps/command.hpp"
#include "apps/sensor_rate_options.hpp"
#include "core/config.hpp"
#include "datasets/loader.hpp"
#include "datasets/protocol.hpp"
#include "metrics/pose_errors.hpp"
#include "pipeline/train/geometric_stage.hpp"
#include "pipeline/train/pose_init.hpp"
#include "pipeline/run/trajectory_files.hpp"
#include "io/pose_graph_svg.hpp"
#include "posegraph/annealed_run.hpp"
#include "posegraph/staged_graph_run.hpp"
#include "posegraph/edge_reseeding.hpp"
#include "posegraph/standin_features.hpp"

namespace sgnlf::app {
namespace {

struct PoseGraphArgs {
  std::string data, out, init = "noisy", graph = "sequential", graph_config;
  double confidence_start = 0.5;
  int steps = 300, per_call = 10;
  posegraph::GeometricConfig cfg;
  double tau_scale = 1.5, lr_final = 0.05;
  posegraph::ReseedConfig reseed;
  int reseed_rounds = 0;
  LoadOptions load;
  SensorRateOptions sensor_rate;
};

const Registrar reg("posegraph", "Run the geometric pose optimiser alone on a dataset", [](CLI::App& sub) {
  auto a = std::make_shared<PoseGraphArgs>();
  a->cfg.points_per_frame = 4000;
  a->cfg.threads = 2;
  a->cfg.lr_rotation = 1e-2;
  a->cfg.lr_translation = 1e-1;
  sub.add_option("--data", a->data, "Dataset folder (synthetic or real layout)")->required();
  sub.add_option("--pose-init", a->init, "Initial poses: noisy (protocol §3), identity, gt or odometry")
      ->check(CLI::IsMember({"noisy", "identity", "gt", "odometry"}));
  sub.add_option("--steps", a->steps, "Adam steps in all");
  sub.add_option("--per-call", a->per_call, "Steps per call (a fresh Adam each call)");
  sub.add_option("--points", a->cfg.points_per_frame, "Points kept per frame");
  sub.add_option("--tau-scale", a->tau_scale, "τ reaches this scale at the end (the presets' 1.5; GeoNLF's published 0.3 KITTI / 0.5 nuScenes when < 0)");
  sub.add_option("--lr-rot", a->cfg.lr_rotation, "Adam learning rate of the rotations (rad)");
  sub.add_option("--lr-trans", a->cfg.lr_translation, "Adam learning rate of the translations (m)");
  sub.add_option("--lr-final", a->lr_final, "Learning rates decay exponentially to this factor at the end");
  sub.add_option("--offsets", a->cfg.edge_offsets, "Edges (i, i + k) for these k")->delimiter(',');
  sub.add_option("--residual", a->cfg.residual, "Direction term: point_to_point (GeoNLF's robust Chamfer) or point_to_plane")
      ->check(CLI::IsMember({"point_to_point", "point_to_plane"}));
  sub.add_option("--reseed-rounds", a->reseed_rounds, "After the sequential alignment, re-seed edges whose motion spikes off both neighbours' (posegraph/edge_reseeding.hpp): passes over the edges, 0 = none");
  sub.add_option("--reseed-steps", a->reseed.steps, "Refinement steps per re-seeding hypothesis");
  sub.add_option("--reseed-min-difference", a->reseed.min_difference_m, "Re-seed an edge whose relative translation differs from both neighbours' by more than this while they agree within it (m)");
  sub.add_option("--reseed-judge", a->reseed.judge, "Residual that decides a re-seeding: point_to_point or point_to_plane (default: the stage's)");
  sub.add_option("--reseed-min-gain", a->reseed.min_gain, "Keep a re-seeding when the crossing edges' loss falls by more than this fraction");
  sub.add_flag("--reseed-judge-total", a->reseed.judge_total, "Keep a re-seeding when the whole graph's loss falls (and the crossing edges' by min-gain), instead of bounding the other edges' rise by min-gain");
  sub.add_flag("--reseed-frames", a->reseed.frames, "Also re-seed single frames whose two edges both differ from their outer neighbours' (a frame halfway between its neighbours; posegraph/edge_reseeding.hpp)");
  sub.add_option("--out", a->out, "Folder for trajectories/ and posegraph_log.json");
  sub.add_option("--graph", a->graph, "Pose graph: sequential (GeoNLF) or confidence (SG-NLF, stand-in features)")
      ->check(CLI::IsMember({"sequential", "confidence"}));
  sub.add_option("--graph-config", a->graph_config, "JSON file of the confidence graph's parameters (posegraph/confidence_graph_config.hpp)");
  sub.add_option("--confidence-start", a->confidence_start, "Fraction of the calls on the sequential graph before the first confidence graph");
  sub.add_option("--sequence", a->load.sequence, "Sequence / drive / scene of a real layout");
  sub.add_option("--start", a->load.start, "First frame id of the window");
  sub.add_option("--frames", a->load.frames, "Frames in the window");
  a->sensor_rate.add(sub);
  return std::function<int()>([a] {
    a->sensor_rate.apply(a->load);
    if (a->steps < 1 || a->per_call < 1) throw ConfigError("--steps and --per-call must be >= 1");
    if (a->graph == "sequential" && !a->graph_config.empty())
      throw ConfigError("--graph-config needs --graph confidence");
    a->load.validate();
    const Dataset d = load_dataset(a->data, a->load);
    if (!d.has_reference_poses)
      throw ConfigError(a->data + ": scans without reference poses; posegraph scores the "
                        "alignment against them (use sgnlf reconstruct or train --pose-init odometry)");
    pipeline::PoseInitConfig pi;
    pi.init = a->init;
    const std::vector<Pose> init = pipeline::initial_poses(d, pi);
    a->cfg.tau_scale = pipeline::geometric_tau_scale(a->tau_scale, d.sensor);
    a->cfg.steps = a->per_call;
    a->cfg.validate();
    std::vector<std::vector<PointXYZI>> scans;
    for (const auto& f : d.frames) scans.push_back(f.points);
    auto clouds = std::make_shared<const std::vector<posegraph::FrameCloud>>(
        a->cfg.clouds(scans));
    auto loss = std::make_shared<const posegraph::GraphLoss>(
        clouds, posegraph::sequential_edges(int(d.frames.size()), a->cfg.edge_offsets),
        a->cfg.min_distance, a->cfg.threads, a->cfg.direction());
    const std::vector<Pose> gt = gt_poses(d);
    std::vector<Pose> T = init;
    Json log = Json::array();
    auto report = [&](int call, double progress, const posegraph::GeometricResult* r) {
      const auto e = metrics::compute_pose_errors(T, gt);
      std::printf("call %3d  progress %.3f  loss %10.5f  ATE %.3f m (horizontal %.3f)  RPE %.2f cm "
                  "%.3f deg\n", call, progress, r ? r->loss_after : 0.0, e.ate_m, e.ate_h_m,
                  e.rpe_t_cm, e.rpe_r_deg);
      std::fflush(stdout);
      log.push_back(Json{{"call", call}, {"progress", progress}, {"ate_m", e.ate_m},
                         {"ate_h_m", e.ate_h_m},
                         {"ate_reference", d.planar_reference || e.planar_reference ? "horizontal" : "3d"},
                         {"rpe_t_cm", e.rpe_t_cm}, {"rpe_r_deg", e.rpe_r_deg},
                         {"loss", r ? Json(r->loss_after) : Json(nullptr)}});
    };
    report(0, 0.0, nullptr);
    posegraph::AnnealConfig an;
    an.steps = a->steps;
    an.per_call = a->per_call;
    an.lr_final = a->lr_final;
    auto on_call = [&](int k, double clock, const posegraph::GeometricResult& r) {
      report(k, clock, &r);
    };
    Json graphs = Json::array();
    Json graph_cfg_json = nullptr, reseed_log = nullptr;
    if (a->graph == "sequential") {
      posegraph::run_annealed(loss, a->cfg, an, T, on_call);
      if (a->reseed_rounds > 0) {
        a->reseed.max_rounds = a->reseed_rounds;
        const auto rs = posegraph::reseed_edges(
            loss, a->cfg, a->lr_final, a->reseed, T,
            posegraph::make_judge_loss(*loss, scans, a->cfg, a->reseed));
        for (const auto& t : rs.trials) {
          char what[48];
          if (t.frame >= 0)
            std::snprintf(what, sizeof what, "frame %d", t.frame);
          else
            std::snprintf(what, sizeof what, "edge %d-%d", t.edge, t.edge + 1);
          char total[64] = "";
          if (a->reseed.judge_total)
            std::snprintf(total, sizeof total, ", all %.5f -> %.5f", t.total_before, t.total_after);
          std::printf("reseed round %d %s (%.3f m off the neighbours): local %.5f -> "
                      "%.5f (stage %.5f -> %.5f), other edges %.5f -> %.5f%s%s\n", t.round, what,
                      t.difference_m, t.crossing_before, t.crossing_after,
                      t.stage_crossing_before, t.stage_crossing_after, t.rest_before,
                      t.rest_after, total, t.kept ? "  kept" : "");
        }
        reseed_log = posegraph::reseed_json(rs);
        report(int(log.size()), 1.0, nullptr);
      }
    } else {
      posegraph::ConfidenceGraphConfig gc;
      gc.sequential_offsets = a->cfg.edge_offsets;
      gc.threads = a->cfg.threads;
      if (!a->graph_config.empty()) {
        Json j = load_config_file(a->graph_config);
        if (!j.contains("sequential_offsets")) j["sequential_offsets"] = gc.sequential_offsets;
        if (!j.contains("threads")) j["threads"] = gc.threads;
        gc = posegraph::ConfidenceGraphConfig::from_json(j, a->graph_config);
      }
      graph_cfg_json = gc.to_json();
      posegraph::StagedGraphConfig sc;
      sc.anneal = an;
      sc.confidence_start = a->confidence_start;
      const auto features = posegraph::standin_fourier_features({});
      const std::filesystem::path gdir = std::filesystem::path(a->out) / "graphs";
      if (!a->out.empty()) std::filesystem::create_directories(gdir);
      posegraph::run_staged_graph(
          clouds, a->cfg, sc, gc, features, T, on_call, [&](const posegraph::GraphEvaluation& e) {
            const auto& g = e.graph;
            std::printf("graph after call %d: %zu candidates, %zu non-adjacent edges kept "
                        "(threshold %.4f = %.4f + kappa * %.4f)\n",
                        e.after_call, g.pairs.size(), g.non_adjacent_edges(), g.threshold,
                        g.sequential_mean, g.sequential_std);
            graphs.push_back(Json{{"after_call", e.after_call},
                                  {"non_adjacent_edges", g.non_adjacent_edges()},
                                  {"candidates", g.pairs.size()},
                                  {"threshold", std::isfinite(g.threshold) ? Json(g.threshold) : Json(nullptr)}});
            if (a->out.empty()) return;
            const std::string stem = (gdir / ("graph_after_call_" + std::to_string(e.after_call))).string();
            Json gj = posegraph::confidence_graph_json(g);
            gj["after_call"] = e.after_call;
            gj["features"] = features.name;
            write_json_file(stem + ".json", gj);
            std::vector<io::SvgGraphEdge> edges;
            for (const auto& r : g.pairs)
              if (r.kept) edges.push_back({r.i, r.j, r.weight, r.sequential});
            io::write_pose_graph_svg(stem + ".svg",
                                     d.name + ": confidence graph after call " +
                                         std::to_string(e.after_call) + " (grey: ground truth)",
                                     T, edges, gt);
          });
    }
    if (!a->out.empty()) {
      pipeline::write_run_trajectories(a->out, d, init, T);
      write_json_file((std::filesystem::path(a->out) / "posegraph_log.json").string(),
                      Json{{"dataset", d.name}, {"pose_init", a->init}, {"points", a->cfg.points_per_frame},
                           {"tau_scale", a->cfg.tau_scale}, {"lr_rot", a->cfg.lr_rotation},
                           {"residual", a->cfg.residual},
                           {"lr_trans", a->cfg.lr_translation}, {"graph", a->graph},
                           {"graph_config", graph_cfg_json}, {"confidence_start", a->confidence_start},
                           {"graphs", graphs}, {"reseed", reseed_log}, {"calls", log}});
    }
    return 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
