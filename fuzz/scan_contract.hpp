// The contract the point-cloud fuzz targets check (fuzz_scan_pcd, fuzz_scan_ply): what
// io::read_scan accepts from the input (written to `name`, whose extension picks the reader)
// must hold together (points + dropped = records, ring and time in step with the points), and
// must come back bit for bit through the project's writer `write` and reader `read`.
#pragma once
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "fuzz_input.hpp"
#include "io/cloud_writers.hpp"
#include "io/scan_io.hpp"

namespace sgnlf::fuzz {

using ScanWriter = std::function<void(const std::string&, const std::vector<PointXYZI>&, const io::ScanExtras*)>;
using ScanReader = std::function<std::vector<PointXYZI>(const std::string&, io::ScanExtras*)>;

inline int check_scan_contract(const std::string& name, const uint8_t* data, size_t size,
                               const ScanWriter& write, const ScanReader& read) {
  const std::string path = write_input(name, data, size);
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
  const std::string again = scratch_dir() + "/again-" + name;
  write(again, pts, &ex);
  io::ScanExtras ex2;
  const auto back = read(again, &ex2);
  if (back.size() != pts.size() || std::memcmp(back.data(), pts.data(), pts.size() * sizeof(PointXYZI)) != 0 ||
      ex2.ring != ex.ring || ex2.time.size() != ex.time.size() ||
      (!ex.time.empty() && std::memcmp(ex2.time.data(), ex.time.data(), ex.time.size() * 8) != 0))
    __builtin_trap();
  return 0;
}

}  // namespace sgnlf::fuzz
