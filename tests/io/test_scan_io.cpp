// Scan readers: round trips, and every bad input gives an IoError naming the file and offset.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "core/error.hpp"
#include "io/scan_io.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;

namespace {
void write_floats(const std::string& path, const std::vector<float>& v, size_t extra_bytes = 0) {
  std::vector<char> b(v.size() * 4 + extra_bytes, 0);
  if (!v.empty()) std::memcpy(b.data(), v.data(), v.size() * 4);  // memcpy from null: UB (UBSan)
  io::write_file_bytes(path, b.data(), b.size());
}
bool message_has(const std::function<void()>& f, const std::string& a, const std::string& b = "") {
  try {
    f();
  } catch (const IoError& e) {
    const std::string m = e.what();
    INFO(m);
    return m.find(a) != std::string::npos && m.find(b) != std::string::npos;
  }
  return false;
}
}  // namespace

TEST_CASE("KITTI .bin round trip", "[io]") {
  const std::string dir = test::temp_dir("io_bin");
  std::vector<PointXYZI> pts = {{1, 2, 3, 0.5f}, {-4, 5.5f, -6, 0.25f}};
  io::write_kitti_bin(dir + "/a.bin", pts);
  io::ScanReadStats st;
  const auto back = io::read_kitti_bin(dir + "/a.bin", &st);
  REQUIRE(back.size() == 2);
  CHECK(st.records == 2);
  CHECK(st.non_finite == 0);
  CHECK(st.max_intensity == 0.5f);
  CHECK(back[1].y == 5.5f);
  CHECK(back[1].intensity == 0.25f);
}

TEST_CASE("nuScenes .pcd.bin: intensity / 255 and rings", "[io]") {
  const std::string dir = test::temp_dir("io_pcdbin");
  write_floats(dir + "/x.pcd.bin", {1, 2, 3, 255, 7, 4, 5, 6, 51, 31});
  std::vector<uint8_t> rings;
  const auto p = io::read_nuscenes_bin(dir + "/x.pcd.bin", nullptr, &rings);
  REQUIRE(p.size() == 2);
  CHECK(p[0].intensity == Approx(1.0));
  CHECK(p[1].intensity == Approx(0.2));
  CHECK(rings == std::vector<uint8_t>{7, 31});
  CHECK(io::read_scan(dir + "/x.pcd.bin").size() == 2);  // dispatch by name
}

TEST_CASE("bad scans: truncated, misaligned, empty, NaN/Inf", "[io][bad-input]") {
  const std::string dir = test::temp_dir("io_bad_scans");
  write_floats(dir + "/trunc.bin", {1, 2, 3, 4, 5, 6, 7, 8}, 6);  // 2 records + 6 bytes
  CHECK(message_has([&] { io::read_kitti_bin(dir + "/trunc.bin"); }, "trunc.bin", "byte offset 32"));
  write_floats(dir + "/mis.pcd.bin", {1, 2, 3, 4, 5, 6, 7, 8});  // 32 bytes: not a multiple of 20
  CHECK(message_has([&] { io::read_nuscenes_bin(dir + "/mis.pcd.bin"); }, "mis.pcd.bin", "byte offset 20"));
  write_floats(dir + "/empty.bin", {});
  CHECK(message_has([&] { io::read_kitti_bin(dir + "/empty.bin"); }, "empty.bin", "empty scan"));
  CHECK(message_has([&] { io::read_kitti_bin(dir + "/missing.bin"); }, "missing.bin", "cannot open"));
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  write_floats(dir + "/nan.bin", {1, 2, 3, 0.5f, nan, 0, 0, 0.1f, 0, inf, 0, 0.1f, 4, 5, 6, 0.2f});
  io::ScanReadStats st;
  const auto p = io::read_kitti_bin(dir + "/nan.bin", &st);
  CHECK(p.size() == 2);  // the NaN and the Inf point are dropped and counted
  CHECK(st.records == 4);
  CHECK(st.non_finite == 2);
  write_floats(dir + "/allnan.bin", {nan, 0, 0, 0});
  CHECK(message_has([&] { io::read_kitti_bin(dir + "/allnan.bin"); }, "allnan.bin", "empty scan"));
}
