// Test fixture: a tiny synthetic KITTI-360-like sequence (14 frames of 16 × 128 pixels, test
// frame 13), simulated in memory once per test binary (or written to disk), and the smoke
// config shrunk further.
#pragma once
#include "datasets/protocol.hpp"
#include "datasets/simulate.hpp"
#include "pipeline/presets.hpp"
#include "pipeline/scene.hpp"
#include "pipeline/session.hpp"

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
