// JSON read by the strict loader (core/config.hpp ConfigReader): sensor descriptions
// (sensor_from_json: --sensor files, sensor.json of the synthetic layout), dataset load options
// (run.json "dataset_options") and the synthetic layout's sgnlf_dataset.json (through
// load_dataset on a tiny tree whose description is the input). The first byte picks the reader.
#include <filesystem>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "datasets/loader.hpp"
#include "fuzz_input.hpp"
#include "geometry/sensor.hpp"
#include "io/scan_io.hpp"
#include "io/trajectory_io.hpp"

namespace {
namespace fs = std::filesystem;

// A synthetic-layout tree (frames 0..3) whose sgnlf_dataset.json the input replaces.
std::string synthetic_tree() {
  static const std::string root = [] {
    const std::string r = sgnlf::fuzz::scratch_dir() + "/synthetic";
    const std::string drive = "2013_05_28_drive_0000_sync";
    fs::create_directories(r + "/calibration");
    fs::create_directories(r + "/data_poses/" + drive);
    const std::string id = "1 0 0 0 0 1 0 0 0 0 1 0";
    sgnlf::write_text_file(r + "/calibration/calib_cam_to_pose.txt", "image_00: " + id + "\n");
    sgnlf::write_text_file(r + "/calibration/calib_cam_to_velo.txt", id + "\n");
    std::string poses;
    for (int k = 0; k < 4; ++k) {
      poses += std::to_string(k) + " " + id + "\n";
      char n[32];
      std::snprintf(n, sizeof n, "/%010d.bin", k);
      sgnlf::io::write_kitti_bin(r + "/data_3d_raw/" + drive + "/velodyne_points/data" + n,
                                 {{5.f, 1.f, -1.f, 0.3f}, {-7.f, 2.f, 0.5f, 0.6f}});
    }
    sgnlf::write_text_file(r + "/data_poses/" + drive + "/poses.txt", poses);
    sgnlf::write_json_file(r + "/sensor.json", sgnlf::sensor_to_json(sgnlf::Sensor{"s", 8, 64, 2.0, 26.9, 80.0, 0.0, 10.0, sgnlf::SweepTiming{}}));
    return r;
  }();
  return root;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool quiet = (sgnlf::log::set_level(sgnlf::log::Level::error), true);
  (void)quiet;
  if (size == 0) return 0;
  const int which = data[0] % 3;
  try {
    if (which == 2) {
      const std::string root = synthetic_tree();
      sgnlf::fuzz::write_input("synthetic/sgnlf_dataset.json", data + 1, size - 1);
      sgnlf::LoadOptions o;
      o.load_points = false;
      sgnlf::load_dataset(root, o);
      return 0;
    }
    const std::string path = sgnlf::fuzz::write_input("config.json", data + 1, size - 1);
    const sgnlf::Json j = sgnlf::load_json_file(path);
    if (which == 0) {
      const sgnlf::Sensor s = sgnlf::sensor_from_json(j, path);
      if (long(s.height) * s.width > sgnlf::kMaxSensorPixels) __builtin_trap();
    } else {
      sgnlf::LoadOptions::from_json(j, path).validate();
    }
  } catch (const sgnlf::Error&) {
  }
  return 0;
}
