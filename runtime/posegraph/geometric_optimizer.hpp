// GeoNLF's graph-based geometric pose optimiser (method.md §3), device-free: before each epoch,
// a few pose-only Adam steps on the robust Chamfer pose-graph loss (graph_loss.hpp) over the
// frames' fixed subsampled scans. Each run() starts a FRESH Adam (β 0.9/0.999) on zero
// corrections ξ_k = (ω_k, u_k) on top of the current poses (method.md §0), moves every frame
// (none held fixed) and writes the corrected poses back.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "posegraph/graph_loss.hpp"
#include "posegraph/pose_adam.hpp"

namespace sgnlf::posegraph {

// Embedded whole where it is configured (the training config's "geometric.optimizer"), through
// its field list; `steps` is not a key there: whoever runs the optimiser sets it per call (the
// training's geometric schedule, sgnlf posegraph's --per-call).
struct GeometricConfig {
  std::vector<int> edge_offsets = {1, 2};  // GeoNLF: (i, i+1), (i, i+2)
  int steps = 10;                 // Adam steps per run() call
  double lr_rotation = 5e-3;      // rad; see the recovery test for the tuning
  double lr_translation = 2e-2;   // m
  double tau_scale = 0.3;         // τ = tau_scale · progress (0.3 KITTI, 0.5 nuScenes)
  double min_distance = 0.15;     // m, clamp of d inside the robust weights
  size_t points_per_frame = 12000;  // from_scans: points kept per frame (0 = all)
  uint64_t seed = 1;              // from_scans: subsample seed
  int threads = 1;                // direction terms in parallel; results identical for any value
  // Direction term: "point_to_point" (GeoNLF's robust Chamfer) or "point_to_plane"
  // (point_to_plane.hpp; its clouds need normals, estimated with `normals`).
  std::string residual = "point_to_point";
  NormalOptions normals;

  // The keys (core/config_fields.hpp): all but `steps`; the rules are validate()'s, the closed
  // ranges listed here too.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("edge_offsets", s.edge_offsets);
    v("lr_rotation", s.lr_rotation);
    v("lr_translation", s.lr_translation);
    v("tau_scale", s.tau_scale);
    v("min_distance", s.min_distance);
    v("points_per_frame", s.points_per_frame, size_t(0), size_t(1) << 24);
    v("seed", s.seed);
    v("threads", s.threads, 1, 256);
    v("residual", s.residual);
    v.section("normals", s.normals);
  }
  // Throws sgnlf::ConfigError naming `where`, the field and its value.
  void validate(const std::string& where = "GeometricConfig") const;
  // The direction term `residual` names, for a GraphLoss.
  DirectionFn direction() const;
  // make_frame_clouds(scans, points_per_frame, seed), with normals when the residual needs them.
  std::vector<FrameCloud> clouds(const std::vector<std::vector<PointXYZI>>& scans) const;
  AdamSettings adam() const;
};

struct GeometricResult {
  int steps = 0;
  double tau = 0.0;
  double loss_before = 0.0;  // at the poses given to run()
  double loss_after = 0.0;   // at the poses written back (one extra loss evaluation)
  double max_rotation_rad = 0.0;     // largest |ω| applied to a frame in this call
  double max_translation_m = 0.0;    // largest |u| applied to a frame in this call
};

class GeometricOptimizer {
 public:
  // GeoNLF default: robust Chamfer over sequential_edges(frames, cfg.edge_offsets), or over
  // `edges` when given (e.g. SG-NLF's weighted pose graph).
  GeometricOptimizer(std::vector<FrameCloud> clouds, const GeometricConfig& cfg,
                     std::vector<Edge> edges = {});
  // Clouds from the scans (LiDAR frames): make_frame_clouds(scans, cfg.points_per_frame,
  // cfg.seed), then the constructor above.
  static GeometricOptimizer from_scans(const std::vector<std::vector<PointXYZI>>& scans,
                                       const GeometricConfig& cfg, std::vector<Edge> edges = {});
  // Any loss over `frames` poses (a wrapped or replaced GraphLoss).
  GeometricOptimizer(PoseLoss loss, size_t frames, const GeometricConfig& cfg);

  // progress ∈ [0, 1] sets τ = tau_scale · progress. T_world_lidar.size() must equal the
  // number of frames and every pose must be finite (sgnlf::Error otherwise); a non-finite loss
  // throws sgnlf::NumericError.
  GeometricResult run(std::vector<Pose>& T_world_lidar, double progress) const;

  size_t frames() const { return frames_; }
  const GeometricConfig& config() const { return cfg_; }

 private:
  PoseLoss loss_;
  size_t frames_;
  GeometricConfig cfg_;
};

}  // namespace sgnlf::posegraph
