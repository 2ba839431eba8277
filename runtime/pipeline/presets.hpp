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
// The preset's JSON text parsed; ConfigError naming the known presets when absent.
Json preset_json(const std::string& method, const std::string& preset);
// Preset merged with `overrides`, read strictly and validated.
TrainConfig resolve_config(const std::string& method, const std::string& preset,
                           const Json& overrides = Json::object());

}  // namespace sgnlf::pipeline
