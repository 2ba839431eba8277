// The LiDAR-NeRF training configuration (method.md §0–1): field sizes, ray sampling and loss
// weights (render::RenderConfig), optimiser and schedule. Plain structs with defaults (the `paper` values) and
// validate(); JSON through ConfigReader with unknown keys rejected. Presets are JSON files in
// runtime/pipeline/config/presets/, embedded into the binary (presets.hpp).
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "core/config_fwd.hpp"
#include "field/adam_config.hpp"
#include "field/hash_grid_config.hpp"
#include "pipeline/config/consistency_config.hpp"
#include "pipeline/config/lidar4d_config.hpp"
#include "pipeline/config/pose_free_config.hpp"
#include "pipeline/config/pose_graph_config.hpp"
#include "pipeline/config/spectral_field_config.hpp"
#include "render/render_config.hpp"

namespace sgnlf::pipeline {

// Hash grid + density MLP + LiDAR head (method.md §0 "Field"). The hash grid's own config is
// embedded whole ("grid": every key of field::HashGridConfig, checked by its validate()); the
// defaults are the paper's (16 levels × 2 features, 2^19 entries, base 16, scale 1.6625, the
// deterministic backward).
struct FieldSizes {
  field::HashGridConfig grid;
  int density_hidden = 64;   // encoding → 64 (ReLU) → 1 + geo_features
  int geo_features = 15;
  int head_hidden = 64;      // 3 layers of 64
  int head_layers = 3;
  int dir_frequencies = 12;  // 72-dim frequency encoding of the view direction
  // The keys and ranges (core/config_fields.hpp).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.section("grid", s.grid);
    v("density_hidden", s.density_hidden, 8, 256);
    v("geo_features", s.geo_features, 1, 63);
    v("head_hidden", s.head_hidden, 8, 256);
    v("head_layers", s.head_layers, 1, 8);
    v("dir_frequencies", s.dir_frequencies, 0, 16);
  }
  void validate(const std::string& where) const;  // the ranges of fields(), grid.validate()
};

// Adam with exponential learning-rate decay to lr·final_factor (method.md §0 "Optimiser"); the
// optimiser's own config is embedded whole ("adam": field::AdamConfig).
struct OptimConfig {
  double lr = 1e-2;
  double final_factor = 0.1;
  field::AdamConfig adam;  // β1 0.9, β2 0.99, ε 1e-15
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("lr", s.lr, 1e-8, 1e6);
    v("final_factor", s.final_factor, 1e-6, 1.0);
    v.section("adam", s.adam);
  }
  void validate(const std::string& where) const;  // the ranges of fields(), adam.validate()
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
  // The optional sections. pose_free is the pose-free methods' keys (set exactly when the method
  // is one: methods/method.hpp, ConfigSections). The others are on exactly when present in the
  // JSON, and a method may carry only those its ConfigSections lists (another is an unknown key);
  // the presence is the only switch (an "enabled" key is refused), and the predicates below are
  // the only place that reads it.
  std::optional<PoseFreeConfig> pose_free;          // pose-free methods (GeoNLF, SG-NLF)
  std::optional<SpectralFieldConfig> spectral;      // SG-NLF's hybrid field
  std::optional<PoseGraphConfig> pose_graph;        // SG-NLF's confidence-aware pose graph
  std::optional<ConsistencyConfig> consistency;     // SG-NLF's adversarial consistency
  std::optional<Lidar4DConfig> lidar4d;             // LiDAR4D's 4D field and its losses

  bool is_pose_free() const { return pose_free.has_value(); }
  bool hybrid_encoder() const { return spectral.has_value(); }
  bool confidence_graph() const { return pose_graph.has_value(); }
  bool consistency_term() const { return consistency.has_value(); }
  bool four_d_encoder() const { return lidar4d.has_value(); }
  bool flow_supervision() const { return lidar4d && lidar4d->flow.has_value(); }
  bool ray_drop_refinement() const { return lidar4d && lidar4d->refine.has_value(); }
  bool geometric_stage() const { return pose_free && pose_free->geometric.has_value(); }
  bool reweighting() const { return pose_free && pose_free->reweight.has_value(); }

  void validate() const;
  // Hash of the resolved config (checkpoints refuse to resume under a different config); the
  // thread counts are counted at one value (train_config.cpp).
  uint64_t hash() const;
};

// Reads a config (all keys optional; defaults = the struct defaults) and validates it.
TrainConfig train_config_from_json(const Json& j, const std::string& where);
Json train_config_to_json(const TrainConfig& c);
// The hash of a config as train_config_to_json writes it (TrainConfig::hash() is this of its
// JSON): FNV-1a 64 of the compact JSON with the thread counts (geometric.optimizer.threads,
// pose_graph.threads) at 2. For the configs that results record (tests/pipeline/
// test_committed_configs.cpp).
uint64_t config_json_hash(Json resolved);
// The schema of the training config's sections, each described by its field list (field,
// render, optim, schedule, the pose-free sections, spectral, consistency, and pose_graph with
// the confidence graph's keys that sit in it): per key its type, default and range
// (core/config_fields.hpp), from the same lists as the reader, writer and validate(); a nested
// config (spectral's psi, loss, fusion; consistency's discriminator) with its keys under
// "fields"; a top-level key (coarse_to_fine) is described in place.
Json train_config_schema();
// Merges `overrides` onto `base`: nested objects key by key, other values replaced, and a null
// value (`"pose_graph": null`: an optional section taken out) recorded as null, so that merged
// layers of overrides still remove it. drop_removed_keys() then applies the removals (JSON merge
// patch, RFC 7386); resolve_config does both before it reads.
Json merge_config_json(Json base, const Json& overrides);
Json drop_removed_keys(Json merged);

}  // namespace sgnlf::pipeline
