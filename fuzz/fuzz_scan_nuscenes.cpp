// nuScenes .pcd.bin scans (float32 × 5 records, rings): io::read_nuscenes_bin.
#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "io/scan_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = sgnlf::fuzz::write_input("scan.pcd.bin", data, size);
  try {
    sgnlf::io::ScanReadStats st;
    std::vector<uint8_t> rings;
    const auto pts = sgnlf::io::read_nuscenes_bin(path, &st, &rings);
    if (pts.size() != rings.size() || st.records * 20 != size) __builtin_trap();
  } catch (const sgnlf::Error&) {
  }
  return 0;
}
