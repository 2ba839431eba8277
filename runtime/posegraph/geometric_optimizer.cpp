// GeoNLF geometric optimiser: config validation and the pose-only Adam loop.
#include "posegraph/geometric_optimizer.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "posegraph/point_to_plane.hpp"

namespace sgnlf::posegraph {
namespace {

void check_field(const std::string& where, bool ok, const char* field, const std::string& value,
                 const char* rule) {
  if (!ok) throw ConfigError(where + "." + field + " = " + value + ": " + rule);
}

std::string str(double v) { return std::to_string(v); }

void check_poses(const std::vector<Pose>& T, size_t frames) {
  require(T.size() == frames, "GeometricOptimizer::run: " + std::to_string(T.size()) +
                                  " poses for " + std::to_string(frames) + " frames");
  for (size_t k = 0; k < T.size(); ++k)
    require(T[k].matrix().allFinite(),
            "GeometricOptimizer::run: pose of frame " + std::to_string(k) + " is not finite");
}

}  // namespace

void GeometricConfig::validate(const std::string& w) const {
  check_field(w, !edge_offsets.empty(), "edge_offsets", "[]", "needs at least one offset");
  for (int o : edge_offsets)
    check_field(w, o >= 1, "edge_offsets", std::to_string(o), "must be >= 1");
  check_field(w, steps >= 0, "steps", std::to_string(steps), "must be >= 0");
  check_field(w, std::isfinite(lr_rotation) && lr_rotation > 0, "lr_rotation", str(lr_rotation),
              "must be > 0");
  check_field(w, std::isfinite(lr_translation) && lr_translation > 0, "lr_translation",
              str(lr_translation), "must be > 0");
  check_field(w, std::isfinite(tau_scale) && tau_scale >= 0, "tau_scale", str(tau_scale),
              "must be >= 0");
  check_field(w, std::isfinite(min_distance) && min_distance > 0, "min_distance",
              str(min_distance), "must be > 0");
  check_field(w, threads >= 1, "threads", std::to_string(threads), "must be >= 1");
  check_field(w, residual == "point_to_point" || residual == "point_to_plane", "residual",
              "\"" + residual + "\"", "must be \"point_to_point\" or \"point_to_plane\"");
  normals.validate();
}

DirectionFn GeometricConfig::direction() const {
  return residual == "point_to_plane" ? DirectionFn(point_to_plane_direction)
                                      : DirectionFn(robust_chamfer_direction);
}

std::vector<FrameCloud> GeometricConfig::clouds(
    const std::vector<std::vector<PointXYZI>>& scans) const {
  return make_frame_clouds(scans, points_per_frame, seed,
                           residual == "point_to_plane" ? &normals : nullptr);
}

AdamSettings GeometricConfig::adam() const {
  AdamSettings s;
  s.lr_rotation = lr_rotation;
  s.lr_translation = lr_translation;
  return s;
}

GeometricOptimizer::GeometricOptimizer(std::vector<FrameCloud> clouds,
                                       const GeometricConfig& cfg, std::vector<Edge> edges)
    : frames_(clouds.size()), cfg_(cfg) {
  cfg_.validate();
  if (edges.empty()) edges = sequential_edges(int(frames_), cfg_.edge_offsets);
  auto shared = std::make_shared<const std::vector<FrameCloud>>(std::move(clouds));
  loss_ = GraphLoss::as_pose_loss(std::make_shared<const GraphLoss>(
      std::move(shared), std::move(edges), cfg_.min_distance, cfg_.threads, cfg_.direction()));
}

GeometricOptimizer GeometricOptimizer::from_scans(const std::vector<std::vector<PointXYZI>>& scans,
                                                  const GeometricConfig& cfg,
                                                  std::vector<Edge> edges) {
  cfg.validate();
  return GeometricOptimizer(cfg.clouds(scans), cfg, std::move(edges));
}

GeometricOptimizer::GeometricOptimizer(PoseLoss loss, size_t frames, const GeometricConfig& cfg)
    : loss_(std::move(loss)), frames_(frames), cfg_(cfg) {
  cfg_.validate();
  require(bool(loss_), "GeometricOptimizer: empty loss");
}

GeometricResult GeometricOptimizer::run(std::vector<Pose>& T_world_lidar, double progress) const {
  check_poses(T_world_lidar, frames_);
  require(std::isfinite(progress) && progress >= 0.0 && progress <= 1.0,
          "GeometricOptimizer::run: progress must be in [0, 1], got " + str(progress));
  GeometricResult r;
  r.tau = cfg_.tau_scale * progress;
  const std::vector<Pose> T_base = T_world_lidar;
  std::vector<Vec6> xi(frames_, Vec6::Zero()), grad_xi(frames_);
  std::vector<PoseGrad> grad;
  std::vector<Pose> T = T_base;
  PoseAdam adam(frames_, cfg_.adam());
  auto evaluate = [&](int step) {
    const double loss = loss_(T, r.tau, grad);
    if (!std::isfinite(loss) || grad.size() != frames_)
      throw NumericError("GeometricOptimizer: loss " + str(loss) + " at step " +
                         std::to_string(step) + " (" + std::to_string(grad.size()) +
                         " gradients for " + std::to_string(frames_) + " frames)");
    return loss;
  };
  r.loss_before = evaluate(0);
  for (int s = 0; s < cfg_.steps; ++s) {
    if (s > 0) evaluate(s);
    for (size_t k = 0; k < frames_; ++k)
      grad_xi[k] = decoupled_gradient(T_base[k], xi[k], grad[k]);
    adam.step(xi, grad_xi);
    for (size_t k = 0; k < frames_; ++k) T[k] = corrected_pose(T_base[k], xi[k]);
    r.steps = s + 1;
  }
  r.loss_after = cfg_.steps > 0 ? evaluate(cfg_.steps) : r.loss_before;
  for (size_t k = 0; k < frames_; ++k) {
    r.max_rotation_rad = std::max(r.max_rotation_rad, xi[k].head<3>().norm());
    r.max_translation_m = std::max(r.max_translation_m, xi[k].tail<3>().norm());
  }
  T_world_lidar = T;
  return r;
}

}  // namespace sgnlf::posegraph
