// KITTI / KITTI-360 velodyne .bin scans (float32 × 4 records): io::read_kitti_bin.
#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "io/scan_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = sgnlf::fuzz::write_input("scan.bin", data, size);
  try {
    sgnlf::io::ScanReadStats st;
    const auto pts = sgnlf::io::read_scan(path, &st);
    if (pts.empty() || st.records * 16 != size) __builtin_trap();  // the reader's contract
  } catch (const sgnlf::Error&) {
  }
  return 0;
}
