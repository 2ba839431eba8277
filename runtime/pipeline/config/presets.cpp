// Preset lookup over the table generated from presets/*.json (see CMakeLists.txt).
#include "pipeline/config/presets.hpp"

#include <string_view>
#include <utility>

#include "core/config.hpp"
#include "pipeline/methods/registry.hpp"

namespace sgnlf::pipeline {

// Defined in the generated presets_embedded.cpp: (name, JSON text) pairs.
const PresetTexts& embedded_presets();

std::vector<std::string> preset_names() {
  std::vector<std::string> names;
  for (const auto& [name, text] : embedded_presets()) names.emplace_back(name);
  return names;
}

namespace {
constexpr const char* kOdometrySection = "from_odometry";
constexpr const char* kExtends = "extends";
constexpr int kMaxExtends = 8;  // deeper chains are cycles

std::string known_presets(const PresetTexts& texts) {
  std::string known;
  for (const auto& entry : texts) known += (known.empty() ? "" : ", ") + std::string(entry.first);
  return known;
}

const std::string_view* text_of(const PresetTexts& texts, const std::string& key) {
  for (const auto& entry : texts)
    if (entry.first == key) return &entry.second;
  return nullptr;
}

Json resolve(const std::string& key, const PresetTexts& texts, int depth) {
  const std::string_view* text = text_of(texts, key);
  if (!text) throw ConfigError("no preset '" + key + "' (known: " + known_presets(texts) + ")");
  Json j;
  try {
    j = Json::parse(*text);
  } catch (const Json::parse_error& e) {
    throw ConfigError("embedded preset " + key + ": invalid JSON: " + e.what());
  }
  if (!j.is_object()) throw ConfigError("embedded preset " + key + ": not a JSON object");
  if (!j.contains(kExtends)) return j;
  const Json parent = j.at(kExtends);
  j.erase(kExtends);
  if (!parent.is_string())
    throw ConfigError("embedded preset " + key + ": '" + kExtends + "' is not a preset name");
  const std::string base = parent.get<std::string>();
  if (depth >= kMaxExtends)
    throw ConfigError("embedded preset " + key + ": '" + kExtends + "' chain deeper than " +
                      std::to_string(kMaxExtends) + " (a cycle?)");
  if (!text_of(texts, base))
    throw ConfigError("embedded preset " + key + ": '" + kExtends + "' = \"" + base +
                      "\" is not a preset (known: " + known_presets(texts) + ")");
  return merge_config_json(resolve(base, texts, depth + 1), j);
}

}  // namespace

Json resolve_preset(const std::string& name, const PresetTexts& texts) {
  return resolve(name, texts, 0);
}

namespace {

Json embedded_preset(const std::string& method, const std::string& preset) {
  const std::string key = method + "-" + preset;
  if (!text_of(embedded_presets(), key))
    throw ConfigError("no preset '" + preset + "' for method '" + method + "' (known: " +
                      known_presets(embedded_presets()) + ")");
  return resolve_preset(key, embedded_presets());
}
}  // namespace

Json preset_json(const std::string& method, const std::string& preset) {
  Json j = embedded_preset(method, preset);
  j.erase(kOdometrySection);
  return j;
}

Json odometry_start_json(const std::string& method, const std::string& preset) {
  const Json j = embedded_preset(method, preset);
  if (!j.contains(kOdometrySection)) return Json::object();
  const Json& s = j.at(kOdometrySection);
  if (!s.is_object())
    throw ConfigError("embedded preset " + method + "-" + preset + ": '" + kOdometrySection +
                      "' is not an object");
  return s;
}

namespace {
// The family's preset without the optional sections the method does not carry, so that its
// config and hash are those of a method that never had them (ConfigSections).
Json carried_sections(Json j, const ConfigSections& s) {
  const std::pair<const char*, bool> sections[] = {{"spectral", s.spectral},
                                                   {"pose_graph", s.pose_graph},
                                                   {"consistency", s.consistency},
                                                   {"lidar4d", s.lidar4d}};
  for (const auto& [name, carried] : sections)
    if (!carried) j.erase(name);
  return j;
}
}  // namespace

TrainConfig resolve_config(const std::string& method, const std::string& preset,
                           const Json& overrides, const std::string& overrides_name) {
  const Method& spec = find_method(method);
  const Json family = preset_json(spec.preset_family, preset);
  Json merged = merge_config_json(
      merge_config_json(carried_sections(family, spec.sections), spec.overrides), overrides);
  std::string where = "preset " + method + "-" + preset;
  // A malformed poses.init is left to the strict reader below, which names it.
  const Json* init = merged.contains("poses") && merged["poses"].is_object() &&
                             merged["poses"].contains("init")
                         ? &merged["poses"]["init"]
                         : nullptr;
  const bool from_odometry = init && init->is_string() && init->get<std::string>() == "odometry";
  if (from_odometry) {
    const Json start = odometry_start_json(spec.preset_family, preset);
    if (!start.empty()) {
      // The start replaces the family's keys; the method's overrides (a section it takes out,
      // say) and then the user's still win.
      merged = merge_config_json(
          merge_config_json(carried_sections(merge_config_json(family, start), spec.sections),
                            spec.overrides),
          overrides);
      where += " + " + std::string(kOdometrySection);
    }
  }
  return train_config_from_json(drop_removed_keys(std::move(merged)), where + " + " + overrides_name);
}

TrainConfig resolve_config(const std::string& method, const std::string& preset) {
  return resolve_config(method, preset, Json::object());
}

}  // namespace sgnlf::pipeline
