// The training config JSON (pipeline/config/train_config.hpp, presets.hpp): what `sgnlf train --config
// overrides.json` merges onto a preset (resolve_config), and a whole config as a run's run.json
// holds it (train_config_from_json, read back on resume). The first byte picks the reader and,
// for overrides, the preset. A config that parses must survive its own round trip: written with
// train_config_to_json and read again it is accepted and has the same hash, or the target traps.
#include "core/config.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "fuzz_input.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/config/train_config.hpp"

namespace {

void round_trip(const sgnlf::pipeline::TrainConfig& c) {
  const sgnlf::Json j = sgnlf::pipeline::train_config_to_json(c);
  const sgnlf::pipeline::TrainConfig again = sgnlf::pipeline::train_config_from_json(j, "round trip");
  if (again.hash() != c.hash()) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool quiet = (sgnlf::log::set_level(sgnlf::log::Level::error), true);
  (void)quiet;
  if (size == 0) return 0;
  static const std::vector<std::string> presets = sgnlf::pipeline::preset_names();
  const unsigned which = data[0];
  try {
    const std::string path = sgnlf::fuzz::write_input("config.json", data + 1, size - 1);
    const sgnlf::Json j = sgnlf::load_json_file(path);
    if (which % 2 == 1) {
      round_trip(sgnlf::pipeline::train_config_from_json(j, path));
      return 0;
    }
    // "<method>-<preset>", the method possibly hyphenated (lidar-nerf-quick, sg-nlf-smoke).
    const std::string& name = presets[(which / 2) % presets.size()];
    const size_t dash = name.rfind('-');
    round_trip(sgnlf::pipeline::resolve_config(name.substr(0, dash), name.substr(dash + 1), j));
  } catch (const sgnlf::Error&) {
  }
  return 0;
}
