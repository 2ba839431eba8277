// Named training presets, stored as JSON files in runtime/pipeline/config/presets/ and embedded into
// the binary at configure time: `paper` (method.md §1 published values, for real GPUs),
// `quick` (≤ ~10 min per 64-frame sequence on 2 CPU cores) and `smoke` (CI, seconds).
// A preset says only what differs from another: `"extends": "geonlf-quick"` takes that preset
// whole (itself resolved first) and merges the file's keys on top, nested objects key by key
// (merge_config_json; arrays and values replaced), its from_odometry section included. What a
// run uses and writes into run.json is the resolved, whole config, so the same resolved config
// has the same hash however its preset is written.
#pragma once
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pipeline/config/train_config.hpp"

namespace sgnlf::pipeline {

// Names "<method>-<preset>" of every embedded preset, sorted.
std::vector<std::string> preset_names();
// (name, JSON text) pairs of presets, as embedded (presets_embedded.cpp, generated).
using PresetTexts = std::vector<std::pair<std::string_view, std::string_view>>;
// The preset `name` of `texts` with its "extends" chain resolved; ConfigError naming the preset
// for a missing base, a malformed "extends" or a chain deeper than 8 (a cycle).
Json resolve_preset(const std::string& name, const PresetTexts& texts);
// The preset's JSON, resolved, without its "from_odometry" section; ConfigError naming the
// known presets when absent.
Json preset_json(const std::string& method, const std::string& preset);
// The preset's "from_odometry" section: config keys that replace the preset's when the poses
// start from the built-in odometry (poses.init = "odometry"). A pose-free preset is tuned for the
// protocol's noisy start (≈ 3 m, 20°); the odometry starts within decimetres (docs/studies/odometry),
// where the coarse alignment and the full pose learning rates only add error (measured:
// docs/studies/odometry/pose_free_from_odometry.md). Empty object when the preset has none.
Json odometry_start_json(const std::string& method, const std::string& preset);
// Preset merged with `overrides`, read strictly and validated. When the merged poses.init is
// "odometry", the preset's from_odometry section is applied between the preset and `overrides`
// (the user's keys still win). `overrides_name` names where the overrides came from in errors
// (e.g. "--config my.json").
TrainConfig resolve_config(const std::string& method, const std::string& preset,
                           const Json& overrides,
                           const std::string& overrides_name = "overrides");
// The preset alone (no overrides).
TrainConfig resolve_config(const std::string& method, const std::string& preset);

}  // namespace sgnlf::pipeline
