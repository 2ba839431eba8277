// `sgnlf bake`: a loaded run's static field baked into a bake::BakedScene (docs/baking.md). The
// surfaces are found from the run's training returns under the run's poses (the optimised ones
// for the pose-free methods), the field probed through the model: σ at the lattice's vertices
// (normalised frame, the renderer's scene-box clamp) and the head at the vertices kept.
#pragma once
#include "bake/bake.hpp"
#include "pipeline/run/run_dir.hpp"

namespace sgnlf::pipeline {

// ConfigError for a 4D field (LiDAR4D: one bake per frame time would be needed; not done).
bake::BakedScene bake_run(LoadedRun& run, const std::string& run_dir, const bake::BakeConfig& cfg,
                          bake::BakeStats* stats = nullptr);

}  // namespace sgnlf::pipeline
