// PLY scans (ascii, binary little/big endian, other elements and list properties skipped):
// io::read_ply through read_scan. What it accepts must hold together (points + dropped =
// records, ring and time in step) and come back bit for bit through the big-endian writer.
#include <cstring>

#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "io/cloud_writers.hpp"
#include "io/ply_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sgnlf;
  const std::string path = fuzz::write_input("scan.ply", data, size);
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
  const std::string again = fuzz::scratch_dir() + "/again.ply";
  io::write_ply(again, pts, io::PlyEncoding::kBinaryBigEndian, &ex);
  io::ScanExtras ex2;
  const auto back = io::read_ply(again, nullptr, &ex2);
  if (back.size() != pts.size() || std::memcmp(back.data(), pts.data(), pts.size() * sizeof(PointXYZI)) != 0 ||
      ex2.ring != ex.ring || ex2.time.size() != ex.time.size() ||
      (!ex.time.empty() && std::memcmp(ex2.time.data(), ex.time.data(), ex.time.size() * 8) != 0))
    __builtin_trap();
  return 0;
}
