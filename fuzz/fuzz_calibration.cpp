// Calibration files: KITTI-360 calib_cam_to_pose.txt ("image_00: 12 numbers"),
// calib_cam_to_velo.txt (a bare 3×4 line) and KITTI odometry calib.txt ("Tr: ..."), read as the
// loaders read them (io::read_key_values, io::key_pose with its rigidity check).
#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "io/trajectory_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = sgnlf::fuzz::write_input("calib.txt", data, size);
  try {
    const auto kv = sgnlf::io::read_key_values(path);
    for (const char* key : {"image_00", "", "Tr"}) {
      try {
        const sgnlf::Pose T = sgnlf::io::key_pose(kv, key, path);
        if (!T.matrix().allFinite()) __builtin_trap();
      } catch (const sgnlf::Error&) {
      }
    }
  } catch (const sgnlf::Error&) {
  }
  return 0;
}
