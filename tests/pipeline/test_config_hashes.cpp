// The resolved config of every method x preset (and, for the pose-free ones, its start from the
// odometry) against the hashes committed in config_hashes.json. A refactor of the configs, the
// presets or the method registry must keep every run's config, and so every committed result's
// config hash, as it was; a change that means to move a preset regenerates the file on purpose:
//   SGNLF_WRITE_CONFIG_HASHES=1 build/tests/pipeline/test_pipeline_config "[config-hashes]"
#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>

#include "core/config.hpp"
#include "pipeline/run/method.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/config/train_config.hpp"

using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {
const std::string kFile = std::string(SGNLF_SOURCE_DIR) + "/tests/pipeline/config_hashes.json";

std::string hex(uint64_t h) {
  char b[17];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(h));
  return b;
}

// "method/preset[/odometry]" -> (hash, resolved config) for every resolvable combination.
std::map<std::string, std::pair<std::string, Json>> resolved_now() {
  std::map<std::string, std::pair<std::string, Json>> out;
  for (const auto& m : known_methods()) {
    if (!method_implemented(m)) continue;
    for (const char* p : {"smoke", "quick", "paper"}) {
      const TrainConfig c = resolve_config(m, p);
      out[m + "/" + p] = {hex(c.hash()), train_config_to_json(c)};
      if (c.is_pose_free()) {
        const TrainConfig o = resolve_config(m, p, Json{{"poses", {{"init", "odometry"}}}});
        out[m + "/" + p + "/odometry"] = {hex(o.hash()), train_config_to_json(o)};
      }
    }
  }
  return out;
}
}  // namespace

TEST_CASE("every method's resolved presets keep their committed config hashes",
          "[pipeline][config][config-hashes]") {
  const auto now = resolved_now();
  REQUIRE(now.size() >= 20);
  if (const char* w = std::getenv("SGNLF_WRITE_CONFIG_HASHES"); w && std::string(w) == "1") {
    Json j = Json::object();
    for (const auto& [k, v] : now) j[k] = v.first;
    std::ofstream(kFile) << j.dump(2) << "\n";
    WARN("wrote " << kFile);
  }
  std::ifstream f(kFile);
  REQUIRE(f.good());
  const Json golden = Json::parse(f);
  for (const auto& [k, v] : now) {
    INFO(k << " resolves to " << v.second.dump());
    REQUIRE(golden.contains(k));
    CHECK(golden.at(k).get<std::string>() == v.first);
  }
  for (auto it = golden.begin(); it != golden.end(); ++it) {
    INFO(it.key() << " is in " << kFile << " but no longer resolves");
    CHECK(now.count(it.key()) == 1);
  }
}
