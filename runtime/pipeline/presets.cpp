// Preset lookup over the table generated from presets/*.json (see CMakeLists.txt).
#include "pipeline/presets.hpp"

#include <string_view>
#include <utility>

#include "pipeline/methods/registry.hpp"

namespace sgnlf::pipeline {

// Defined in the generated presets_embedded.cpp: (name, JSON text) pairs.
const std::vector<std::pair<std::string_view, std::string_view>>& embedded_presets();

std::vector<std::string> preset_names() {
  std::vector<std::string> names;
  for (const auto& [name, text] : embedded_presets()) names.emplace_back(name);
  return names;
}

namespace {
constexpr const char* kOdometrySection = "from_odometry";

Json embedded_preset(const std::string& method, const std::string& preset) {
  const std::string key = method + "-" + preset;
  for (const auto& [name, text] : embedded_presets()) {
    if (name != key) continue;
    try {
      return Json::parse(text);
    } catch (const Json::parse_error& e) {
      throw ConfigError("embedded preset " + key + ": invalid JSON: " + e.what());
    }
  }
  std::string known;
  for (const auto& n : preset_names()) known += (known.empty() ? "" : ", ") + n;
  throw ConfigError("no preset '" + preset + "' for method '" + method + "' (known: " + known + ")");
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

TrainConfig resolve_config(const std::string& method, const std::string& preset,
                           const Json& overrides) {
  const Method& spec = find_method(method);
  Json base = preset_json(spec.preset_family, preset);
  // A method without the consistency section drops it from its family's presets, so that its
  // config and hash stay those of a method that never had the term (ConfigSections).
  if (!spec.sections.consistency) base.erase("consistency");
  base = merge_config_json(std::move(base), spec.overrides);
  Json merged = merge_config_json(base, overrides);
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
      merged = merge_config_json(merge_config_json(std::move(base), start), overrides);
      where += " + " + std::string(kOdometrySection);
    }
  }
  return train_config_from_json(merged, where + " + overrides");
}

}  // namespace sgnlf::pipeline
