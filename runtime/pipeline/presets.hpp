// Named training presets, stored as JSON files in runtime/pipeline/presets/ and embedded into
// the binary at configure time: `paper` (method.md §1 published values, for real GPUs),
// `quick` (≤ ~10 min per 64-frame sequence on 2 CPU cores) and `smoke` (CI, seconds).
#pragma once
#include <string>
#include <vector>

#include "pipeline/train_config.hpp"

namespace sgnlf::pipeline {

// Names "<method>-<preset>" of every embedded preset, sorted.
std::vector<std::string> preset_names();
// The preset's JSON text parsed, without its "from_odometry" section; ConfigError naming the
// known presets when absent.
Json preset_json(const std::string& method, const std::string& preset);
// The preset's "from_odometry" section: config keys that replace the preset's when the poses
// start from the built-in odometry (poses.init = "odometry"). A pose-free preset is tuned for the
// protocol's noisy start (≈ 3 m, 20°); the odometry starts within decimetres (results/odometry),
// where the coarse alignment and the full pose learning rates only add error (measured:
// results/odometry/pose_free_from_odometry.md). Empty object when the preset has none.
Json odometry_start_json(const std::string& method, const std::string& preset);
// Preset merged with `overrides`, read strictly and validated. When the merged poses.init is
// "odometry", the preset's from_odometry section is applied between the preset and `overrides`
// (the user's keys still win).
TrainConfig resolve_config(const std::string& method, const std::string& preset,
                           const Json& overrides = Json::object());

}  // namespace sgnlf::pipeline
