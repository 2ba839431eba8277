// The method registry: every row a table can name, what it is built from and whether this
// build implements it. A method is a preset family (presets/<family>-<scale>.json) plus
// overrides, so a control row composes an existing method instead of copying its presets.
#pragma once
#include <string>
#include <vector>

#include "core/config.hpp"

namespace sgnlf::pipeline {

struct MethodSpec {
  std::string name;            // row name in tables and run.json
  std::string preset_family;   // presets/<family>-<scale>.json
  Json overrides;              // applied on top of the preset (before the user's overrides)
  bool pose_free = false;      // poses are parameters (PoseFreeConfig in its config)
  bool implemented = false;
  std::string description;
  bool spectral_field = false; // SG-NLF's hybrid field: the config's "spectral" section
  bool confidence_graph = false;  // SG-NLF's pose graph: the config's "pose_graph" section
  // SG-NLF's adversarial cross-frame consistency: the config's "consistency" section. A method
  // without it drops the section of its family's presets (resolve_config), so that its config
  // and hash stay those of a method that never had the term.
  bool consistency = false;
};

const std::vector<MethodSpec>& method_registry();
// ConfigError naming the known methods when `name` is not one.
const MethodSpec& method_spec(const std::string& name);

}  // namespace sgnlf::pipeline
