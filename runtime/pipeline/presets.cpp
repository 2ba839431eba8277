// Preset lookup over the table generated from presets/*.json (see CMakeLists.txt).
#include "pipeline/presets.hpp"

#include <string_view>
#include <utility>

#include "pipeline/method_registry.hpp"

namespace sgnlf::pipeline {

// Defined in the generated presets_embedded.cpp: (name, JSON text) pairs.
const std::vector<std::pair<std::string_view, std::string_view>>& embedded_presets();

std::vector<std::string> preset_names() {
  std::vector<std::string> names;
  for (const auto& [name, text] : embedded_presets()) names.emplace_back(name);
  return names;
}

Json preset_json(const std::string& method, const std::string& preset) {
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

TrainConfig resolve_config(const std::string& method, const std::string& preset,
                           const Json& overrides) {
  const MethodSpec& spec = method_spec(method);
  Json base = preset_json(spec.preset_family, preset);
  if (!spec.consistency) base.erase("consistency");  // see MethodSpec::consistency
  const Json merged =
      merge_config_json(merge_config_json(std::move(base), spec.overrides), overrides);
  return train_config_from_json(merged, "preset " + method + "-" + preset + " + overrides");
}

}  // namespace sgnlf::pipeline
