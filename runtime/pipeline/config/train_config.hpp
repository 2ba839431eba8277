// The LiDAR-NeRF training configuration (method.md §0–1): field sizes, ray sampling and loss
// weights (render::RenderConfig), optimiser and schedule. Plain structs with defaults (the `paper` values) and
// validate(); JSON through ConfigReader with unknown keys rejected. Presets are JSON files in
// runtime/pipeline/config/presets/, embedded into the binary (presets.hpp).
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "core/config_fwd.hpp"
#include "pipeline/config/consistency_config.hpp"
#include "pipeline/config/lidar4d_config.hpp"
#include "pipeline/config/pose_free_config.hpp"
#include "pipeline/config/pose_graph_config.hpp"
#include "pipeline/config/spectral_field_config.hpp"
#include "render/render_config.hpp"

namespace sgnlf::pipeline {

// Hash grid + density MLP + LiDAR head (method.md §0 "Field").
struct FieldSizes {
  int levels = 16;
  int features_per_level = 2;
  int log2_table_size = 19;
  int base_resolution = 16;
  double per_level_scale = 1.6625;
  int density_hidden = 64;   // encoding → 64 (ReLU) → 1 + geo_features
  int geo_features = 15;
  int head_hidden = 64;      // 3 layers of 64
  int head_layers = 3;
  int dir_frequencies = 12;  // 72-dim frequency encoding of the view direction
  // The keys and ranges (core/config_fields.hpp).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("levels", s.levels, 1, 32);
    v("features_per_level", s.features_per_level, 1, 8);
    v("log2_table_size", s.log2_table_size, 8, 24);
    v("base_resolution", s.base_resolution, 2, 4096);
    v("per_level_scale", s.per_level_scale, 1.0, 4.0);
    v("density_hidden", s.density_hidden, 8, 256);
    v("geo_features", s.geo_features, 1, 63);
    v("head_hidden", s.head_hidden, 8, 256);
    v("head_layers", s.head_layers, 1, 8);
    v("dir_frequencies", s.dir_frequencies, 0, 16);
  }
  void validate(const std::string& where) const;  // the ranges of fields()
};

// Adam with exponential learning-rate decay to lr·final_factor (method.md §0 "Optimiser").
struct OptimConfig {
  double lr = 1e-2;
  double beta1 = 0.9;
  double beta2 = 0.99;
  double eps = 1e-15;
  double final_factor = 0.1;
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("lr", s.lr, 1e-8, 1e6);
    v("beta1", s.beta1, 0.0, 0.999999);
    v("beta2", s.beta2, 0.0, 0.999999999);
    v("eps", s.eps, 1e-30, 1.0);
    v("final_factor", s.final_factor, 1e-6, 1.0);
  }
  void validate(const std::string& where) const;  // the ranges of fields()
  // lr at `step` of `iterations`: lr · final_factor^(step / iterations).
  double lr_at(long step, long iterations) const;
};

struct ScheduleConfig {
  long iterations = 30000;
  int rays_per_batch = 4096;     // rays from one training frame per iteration
  long eval_every = 5000;        // periodic evaluation of the test frames (0 = only at the end)
  long checkpoint_every = 1000;  // checkpoint period (0 = only at the end)
  long log_every = 50;           // loss read back every log_every steps (host sync)
  bool patches_on_even_epochs = true;  // patch batches + gradient loss on even epochs (§1)
  double divergence_factor = 1e3;  // loss > factor · best smoothed loss → divergence
  int render_chunk_rays = 8192;  // rays per chunk when rendering full range images
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("iterations", s.iterations, 1L, 100000000L);
    v("rays_per_batch", s.rays_per_batch, 1, 1 << 20);
    v("eval_every", s.eval_every, 0L, 100000000L);
    v("checkpoint_every", s.checkpoint_every, 0L, 100000000L);
    v("log_every", s.log_every, 1L, 100000000L);
    v("divergence_factor", s.divergence_factor, 1.0, 1e30);
    v("render_chunk_rays", s.render_chunk_rays, 64, 1 << 22);
    v("patches_on_even_epochs", s.patches_on_even_epochs);
  }
  void validate(const std::string& where) const;  // the ranges of fields()
};

struct TrainConfig {
  std::string method = "lidar-nerf";
  std::string preset = "paper";
  FieldSizes field;
  // Sampling, volume rendering and loss weights (render module; lengths in metres).
  render::RenderConfig render;
  OptimConfig optim;
  ScheduleConfig schedule;
  // The optional sections: present exactly when the method carries them (methods/method.hpp,
  // ConfigSections; set by train_config_from_json), absent from the JSON otherwise, so other
  // methods' configs and hashes do not change. A feature is on when its section is present and
  // says so: the predicates below are the only place that decides it.
  std::optional<PoseFreeConfig> pose_free;          // pose-free methods (GeoNLF, SG-NLF)
  std::optional<SpectralFieldConfig> spectral;      // SG-NLF's hybrid field
  std::optional<PoseGraphConfig> pose_graph;        // SG-NLF's confidence-aware pose graph
  std::optional<ConsistencyConfig> consistency;     // SG-NLF's adversarial consistency
  std::optional<Lidar4DConfig> lidar4d;             // LiDAR4D's 4D field and its losses

  bool is_pose_free() const { return pose_free.has_value(); }
  bool hybrid_encoder() const { return spectral && spectral->enabled; }
  bool confidence_graph() const { return pose_graph && pose_graph->enabled; }
  bool consistency_term() const { return consistency && consistency->enabled; }
  bool four_d_encoder() const { return lidar4d.has_value(); }
  bool flow_supervision() const { return lidar4d && lidar4d->flow.enabled; }

  void validate() const;
  // Hash of the resolved config (checkpoints refuse to resume under a different config); the
  // thread counts are counted at one value (train_config.cpp).
  uint64_t hash() const;
};

// Reads a config (all keys optional; defaults = the struct defaults) and validates it.
TrainConfig train_config_from_json(const Json& j, const std::string& where);
Json train_config_to_json(const TrainConfig& c);
// The schema of the training config's sections, each described by its field list (field,
// render, optim, schedule, the pose-free sections, spectral, consistency, and pose_graph with
// the confidence graph's keys that sit in it): per key its type, default and range
// (core/config_fields.hpp), from the same lists as the reader, writer and validate(); a nested
// config (spectral's psi, loss, fusion; consistency's discriminator) with its keys under
// "fields"; a top-level key (coarse_to_fine) is described in place.
Json train_config_schema();
// Applies `overrides` (nested objects merged key by key) to `base` and re-reads strictly.
Json merge_config_json(Json base, const Json& overrides);

}  // namespace sgnlf::pipeline
