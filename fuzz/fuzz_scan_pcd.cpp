// PCD scans (ascii, binary, binary_compressed with LZF): io::read_pcd through read_scan. What
// it accepts must hold together (points + dropped = records, ring and time in step), and must
// come back bit for bit through the project's binary_compressed writer (the LZF compressor).
#include <cstring>

#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "io/cloud_writers.hpp"
#include "io/pcd_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sgnlf;
  const std::string path = fuzz::write_input("scan.pcd", data, size);
  std::vector<PointXYZI> pts;
  io::ScanReadStats st;
  io::ScanExtras ex;
  try {
    pts = io::read_scan(path, &st, &ex);
  } catch (const Error&) {
    return 0;
  }
  if (pts.empty() || pts.size() + st.non_finite != st.records) __builtin_trap();
  if (ex.ring.size() != (ex.has_ring ? pts.size() : 0) || ex.time.size() != (ex.has_time ? pts.size() : 0))
    __builtin_trap();
  const std::string again = fuzz::scratch_dir() + "/again.pcd";
  io::write_pcd(again, pts, io::PcdEncoding::kBinaryCompressed, &ex);
  io::ScanExtras ex2;
  const auto back = io::read_pcd(again, nullptr, &ex2);
  if (back.size() != pts.size() || std::memcmp(back.data(), pts.data(), pts.size() * sizeof(PointXYZI)) != 0 ||
      ex2.ring != ex.ring || ex2.time.size() != ex.time.size() ||
      (!ex.time.empty() && std::memcmp(ex2.time.data(), ex.time.data(), ex.time.size() * 8) != 0))
    __builtin_trap();
  return 0;
}
