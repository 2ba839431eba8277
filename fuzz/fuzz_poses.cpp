// Trajectory text files: KITTI (12 numbers a line), TUM (t tx ty tz qx qy qz qw) and KITTI-360
// poses.txt (frame id + 12 numbers). The first byte picks the reader.
#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "io/trajectory_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string path = sgnlf::fuzz::write_input("poses.txt", data + 1, size - 1);
  try {
    switch (data[0] % 3) {
      case 0: sgnlf::io::read_kitti_poses(path); break;
      case 1: sgnlf::io::read_tum_poses(path); break;
      default: sgnlf::io::read_indexed_poses(path); break;
    }
  } catch (const sgnlf::Error&) {
  }
  return 0;
}
