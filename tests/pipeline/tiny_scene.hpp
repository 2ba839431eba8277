// Test fixture: a tiny synthetic KITTI-360-like sequence (14 frames of 16 × 128 pixels, test
// frame 13), simulated in memory once per test binary (or written to disk), and the smoke
// config shrunk further.
#pragma once
#include "datasets/protocol.hpp"
#include "datasets/simulate.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/model/scene.hpp"
#include "pipeline/run/session.hpp"

namespace sgnlf::test {

inline SimOptions tiny_sim_options() {
  SimOptions o;
  o.sequence = "kitti360-1538";
  o.frames = 14;
  o.width = 128;
  o.height = 16;
  o.threads = 1;
  return o;
}

inline const Dataset& tiny_dataset() {
  static const Dataset d = simulate(tiny_sim_options()).dataset;
  return d;
}

// The same sequence written to `dir` in the synthetic layout (for run-folder tests).
inline void write_tiny_dataset(const std::string& dir) { write_synthetic(simulate(tiny_sim_options()), dir); }

inline pipeline::TrainConfig tiny_config(const Json& extra = Json::object()) {
  Json o{{"schedule", {{"iterations", 12}, {"checkpoint_every", 4}, {"log_every", 2},
                       {"rays_per_batch", 128}, {"render_chunk_rays", 512}}},
         {"render", {{"n_samples", 16}, {"n_importance", 4}}}};
  return pipeline::resolve_config("lidar-nerf", "smoke", pipeline::merge_config_json(o, extra));
}

// The LiDAR4D smoke preset shrunk to the tiny scene (16 steps, checkpoints every 8).
inline pipeline::TrainConfig tiny_lidar4d(const Json& extra = Json::object()) {
  Json o{{"schedule", {{"iterations", 16}, {"checkpoint_every", 8}, {"log_every", 2},
                       {"rays_per_batch", 128}, {"render_chunk_rays", 512}}},
         {"render", {{"n_samples", 16}, {"n_importance", 4}}}};
  return pipeline::resolve_config("lidar4d", "smoke", pipeline::merge_config_json(o, extra));
}

// The SG-NLF smoke preset shrunk to the tiny scene (28 steps, checkpoints every 7, graph from
// epoch 1, λ ramping over steps 4–14); with_consistency adds the adversarial term (every 2
// steps after 4, one-scale discriminator on 8 × 32 renders). Config overrides, as JSON.
inline Json tiny_sgnlf_overrides(bool with_consistency) {
  Json o{{"schedule", {{"iterations", 28}, {"checkpoint_every", 7}, {"log_every", 7},
                       {"rays_per_batch", 128}, {"render_chunk_rays", 512}}},
         {"render", {{"n_samples", 24}}},
         {"geometric", {{"first_steps", 5}, {"steps_per_epoch", 4.0}, {"stop_progress", 1.0},
                        {"optimizer", {{"points_per_frame", 400}}}}},
         {"spectral", {{"fusion", {{"start", 4}, {"end", 14}}}, {"batch", 128},
                       {"points_per_frame", 300}}},
         {"pose_graph", {{"start_epoch", 1}, {"reevaluate_every", 1}, {"match_points", 300},
                         {"min_matches", 5}, {"steps_on_build", 6}}}};
  if (with_consistency)
    o["consistency"] = Json{{"every", 2},          {"warmup_steps", 4},     {"render_rows", 8},
                            {"render_cols", 32},   {"image_row_stride", 1}, {"image_col_stride", 2},
                            {"discriminator", {{"scales", 1}, {"channels", {16, 32, 32}}}}};
  return o;
}

// The request every run-folder test starts from: `method` on the dataset folder `data` with the
// smoke preset's `config`, progress off.
inline pipeline::TrainRequest tiny_request(const std::string& method, const std::string& data,
                                           const pipeline::TrainConfig& config,
                                           const std::string& run_dir, uint64_t seed,
                                           long stop_at = -1, bool resume = true) {
  pipeline::TrainRequest req;
  req.manifest.method = method;
  req.manifest.preset = "smoke";
  req.manifest.dataset = data;
  req.manifest.seed = seed;
  req.manifest.config = config;
  req.run_dir = run_dir;
  req.stop_at = stop_at;
  req.resume = resume;
  req.show_progress = false;
  return req;
}

}  // namespace sgnlf::test
