// make_geometric_stage (see geometric_stage.hpp).
#include "pipeline/geometric_stage.hpp"

#include <memory>

#include "posegraph/annealed_run.hpp"

namespace sgnlf::pipeline {

double geometric_tau_scale(const GeometricScheduleConfig& g, const Sensor& sensor) {
  if (g.tau_scale >= 0.0) return g.tau_scale;
  return sensor.name == "nuscenes" ? 0.5 : 0.3;
}

GeometricStage make_geometric_stage(const Dataset& d, const Scene& scene, const TrainConfig& c) {
  const GeometricScheduleConfig& g = c.pose_free.geometric;
  if (!g.enabled || !c.pose_free.pose_optim.optimize) return {};
  posegraph::GeometricConfig gc;
  gc.edge_offsets = g.edge_offsets;
  gc.lr_rotation = g.lr_rot;
  gc.lr_translation = g.lr_trans;
  gc.tau_scale = geometric_tau_scale(g, d.sensor);
  gc.points_per_frame = size_t(g.points_per_frame);
  gc.seed = 1;
  gc.threads = 2;
  gc.validate();
  std::vector<std::vector<PointXYZI>> scans;
  for (const auto& f : d.frames) scans.push_back(f.points);
  auto clouds = std::make_shared<const std::vector<posegraph::FrameCloud>>(
      posegraph::make_frame_clouds(scans, gc.points_per_frame, gc.seed));
  auto loss = std::make_shared<const posegraph::GraphLoss>(
      clouds, posegraph::sequential_edges(int(d.frames.size()), gc.edge_offsets), gc.min_distance,
      gc.threads);
  const SceneNormalization norm = scene.norm;
  return [g, gc, loss, norm](PoseSet& poses, long epoch, double progress) -> Json {
    const int steps = g.steps_at(epoch, progress);
    if (steps <= 0) return nullptr;
    std::vector<Pose> T(poses.size());
    for (size_t i = 0; i < poses.size(); ++i) T[i] = denormalize_pose(poses.pose(i), norm);
    posegraph::GeometricResult r;
    if (epoch == 0) {  // the coarse alignment
      posegraph::AnnealConfig a;
      a.steps = steps;
      a.lr_final = g.lr_final;
      const auto calls = posegraph::run_annealed(loss, gc, a, T);
      r = calls.back();
      r.loss_before = calls.front().loss_before;
      r.steps = steps;
    } else {  // the shrinking refinement at the final τ and learning rates
      posegraph::GeometricConfig run_cfg = gc;
      run_cfg.steps = steps;
      run_cfg.lr_rotation *= g.lr_final;
      run_cfg.lr_translation *= g.lr_final;
      const posegraph::GeometricOptimizer opt(posegraph::GraphLoss::as_pose_loss(loss),
                                              poses.size(), run_cfg);
      r = opt.run(T, 1.0);
    }
    for (size_t i = 0; i < poses.size(); ++i) poses.set_pose(i, normalize_pose(T[i], norm));
    return Json{{"steps", r.steps},        {"tau", r.tau},
                {"loss_before", r.loss_before}, {"loss_after", r.loss_after},
                {"max_rotation_rad", r.max_rotation_rad},
                {"max_translation_m", r.max_translation_m}};
  };
}

}  // namespace sgnlf::pipeline
