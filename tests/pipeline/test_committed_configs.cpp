// The committed results (results/tables/*/*/results.json) record, for every run, the resolved
// config it trained with and that config's hash; `sgnlf merge` marks a run stale when its hash
// is not its method's current one. This holds every recorded hash to its recorded config
// (config_json_hash, as TrainConfig::hash), and the runs of the current configs to this build:
// read back, their config is exactly the one recorded. When the configs change shape but not
// value (docs/architecture.md, "Configs"), the recorded configs are rewritten
// (scripts/migrations/) and their hashes recomputed with
//   SGNLF_WRITE_COMMITTED_CONFIG_HASHES=1 build/tests/pipeline/test_pipeline_config "[committed-configs]"
// which also sets each combined row's current_config_hash to this build's and requires every
// run's stale flag to come out as it was recorded (a change of shape must not make a current
// run stale, nor a stale one current); then `sgnlf check-tables --render` redraws table.md.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "core/config.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/config/train_config.hpp"

using namespace sgnlf;
using namespace sgnlf::pipeline;
namespace fs = std::filesystem;

TEST_CASE("committed results: every run's config_hash is its config's; current runs read back",
          "[pipeline][config][committed-configs]") {
  const char* w = std::getenv("SGNLF_WRITE_COMMITTED_CONFIG_HASHES");
  const bool write = w && std::string(w) == "1";
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(SGNLF_SOURCE_DIR) / "results/tables"))
    if (e.path().filename() == "results.json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 7);
  size_t runs = 0, current = 0;
  for (const auto& path : files) {
    Json r = load_json_file(path.string());
    for (auto& row : r["rows"]) {
      if (write && row.contains("current_config_hash") && row["current_config_hash"].is_string())
        row["current_config_hash"] =
            hex64(resolve_config(row.value("method", ""), r.value("scale", "")).hash());
      const Json now = row.value("current_config_hash", Json());
      for (auto& s : row["sequences"]) {
        Json& list = s.contains("runs") ? s["runs"] : s;
        auto check = [&](Json& run) {
          if (!run.contains("config") || !run["config"].is_object()) return;
          ++runs;
          const std::string where = path.string() + ": " + row.value("method", "") + " / " +
                                    s.value("sequence", "") + " seed " +
                                    run.value("seed", Json()).dump();
          INFO(where);
          const std::string h = hex64(config_json_hash(run["config"]));
          if (write) {
            run["config_hash"] = h;
            // A combined table's flag, as sgnlf merge computes it, stays what it was.
            if (now.is_string() && s.contains("stale") && s["stale"].is_boolean() &&
                !s.contains("runs"))
              CHECK(s["stale"].get<bool>() == (h != now.get<std::string>()));
            return;
          }
          CHECK(run.value("config_hash", "") == h);
          if (run.value("config_hash", Json()) != now) return;  // a stale run: an older preset
          ++current;
          const TrainConfig c = train_config_from_json(run["config"], where);
          CHECK(train_config_to_json(c) == run["config"]);
          CHECK(hex64(c.hash()) == h);
        };
        if (list.is_array()) {
          bool stale = false;
          for (auto& run : list) {
            check(run);
            stale |= run.value("config_hash", Json()) != now;
          }
          if (write && now.is_string() && s.contains("stale") && s["stale"].is_boolean())
            CHECK(s["stale"].get<bool>() == stale);
        } else {
          check(list);
        }
      }
    }
    if (write) {
      write_json_file(path.string(), r);
      WARN("rewrote the config hashes of " << path.string());
    }
  }
  CHECK(runs >= 50);
  // Enough current runs for the read-back to mean something (24 on 2026-12-07, after GeoNLF's
  // cells were rerun with its moved quick preset).
  if (!write) CHECK(current >= 20);
}
