// nuScenes v1.0 JSON tables (sample_data, ego_pose, calibrated_sensor, sample, scene, sensor),
// read by load_dataset on a tiny tree. The first byte picks the table the input replaces; the
// other tables stay valid, so references into and out of the fuzzed table are exercised.
#include <filesystem>
#include <vector>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "datasets/loader.hpp"
#include "fuzz_input.hpp"
#include "io/scan_io.hpp"

namespace {
namespace fs = std::filesystem;
const char* kTables[] = {"sample_data", "ego_pose", "calibrated_sensor", "sample", "scene", "sensor"};

// The valid tables (also the seed corpus, written by fuzz_make_corpus).
std::vector<sgnlf::Json> valid_tables() {
  using sgnlf::Json;
  auto pose = [](const std::string& tok, double w, double z) {
    return Json{{"token", tok}, {"rotation", {w, 0.0, 0.0, z}}, {"translation", {1.0, 2.0, 0.5}}};
  };
  Json cal = Json::array({pose("c1", 1.0, 0.0)});
  cal[0]["sensor_token"] = "lid";
  Json sd = Json::array();
  for (int k = 0; k < 2; ++k)
    sd.push_back({{"token", "d" + std::to_string(k)}, {"sample_token", "s1"}, {"ego_pose_token", "e" + std::to_string(k)},
                  {"calibrated_sensor_token", "c1"}, {"timestamp", 1000000 + 500000 * k}, {"is_key_frame", k == 0},
                  {"filename", "samples/LIDAR_TOP/a.pcd.bin"}});
  return {sd,
          Json::array({pose("e0", 0.0, 1.0), pose("e1", 1.0, 0.0)}),
          cal,
          Json::array({{{"token", "s1"}, {"scene_token", "sc1"}}}),
          Json::array({{{"token", "sc1"}, {"name", "scene-0001"}}}),
          Json::array({{{"token", "lid"}, {"channel", "LIDAR_TOP"}}})};
}

std::string tree() {
  static const std::string root = [] {
    const std::string r = sgnlf::fuzz::scratch_dir() + "/nuscenes";
    fs::create_directories(r + "/v1.0-mini");
    const std::vector<float> v = {3, 1, -1, 102, 5, -6, 2, 0.5f, 255, 20};
    fs::create_directories(r + "/samples/LIDAR_TOP");
    sgnlf::io::write_file_bytes(r + "/samples/LIDAR_TOP/a.pcd.bin", v.data(), v.size() * 4);
    return r;
  }();
  return root;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool quiet = (sgnlf::log::set_level(sgnlf::log::Level::error), true);
  (void)quiet;
  if (size == 0) return 0;
  static const std::vector<sgnlf::Json> tables = valid_tables();
  static size_t last = 6;  // the table the previous input replaced (6: none written yet)
  const std::string root = tree();
  const size_t which = data[0] % 6;
  for (size_t k = 0; k < 6; ++k)
    if (last == 6 || (k == last && k != which))
      sgnlf::write_json_file(root + "/v1.0-mini/" + kTables[k] + ".json", tables[k]);
  sgnlf::fuzz::write_input(std::string("nuscenes/v1.0-mini/") + kTables[which] + ".json", data + 1, size - 1);
  last = which;
  try {
    sgnlf::LoadOptions o;
    o.frequency = data[0] & 0x80 ? "standard" : "low";
    const sgnlf::Dataset d = sgnlf::load_dataset(root, o);
    for (const auto& f : d.frames)
      if (!f.T_world_lidar.matrix().allFinite()) __builtin_trap();
  } catch (const sgnlf::Error&) {
  }
  return 0;
}
