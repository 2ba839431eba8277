// Parser defects found by reading the code and by the fuzz targets: a KITTI-360
// frame id beyond int, .npy headers claiming huge shapes (allocated before the size check),
// scan files too large to be scans (read whole before), the first NaN point named.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "core/config.hpp"
#include "core/error.hpp"
#include "io/range_array.hpp"
#include "io/scan_io.hpp"
#include "io/trajectory_io.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;
namespace fs = std::filesystem;

TEST_CASE("KITTI-360 poses.txt: a frame id beyond int names the line", "[io][bad-input]") {
  const std::string dir = test::temp_dir("io_poses_id");
  write_text_file(dir + "/poses.txt", "1e10 1 0 0 0 0 1 0 0 0 0 1 0\n");
  CHECK_THROWS_WITH(io::read_indexed_poses(dir + "/poses.txt"),
                    Catch::Contains("poses.txt:1") && Catch::Contains("frame id"));
  write_text_file(dir + "/poses.txt", "2147483647 1 0 0 0 0 1 0 0 0 0 1 0\n");
  CHECK(io::read_indexed_poses(dir + "/poses.txt").count(2147483647) == 1);
}

TEST_CASE("a reflection is not a pose", "[io][bad-input]") {
  const std::string dir = test::temp_dir("io_poses_reflection");
  write_text_file(dir + "/poses.txt", "-1 0 0 0 0 1 0 0 0 0 1 0\n");
  CHECK_THROWS_WITH(io::read_kitti_poses(dir + "/poses.txt"), Catch::Contains("poses.txt:1") && Catch::Contains("reflection"));
}

TEST_CASE(".npy headers are checked against the file size before allocating", "[io][bad-input]") {
  const std::string dir = test::temp_dir("io_npy_shape");
  for (const std::string shape : {"(2147483647, 2147483647, 3)", "(99999999999999999999, 2, 3)",
                                  "(-4, 2, 3)", "(2, 2, 4)", "(2 2, 3)", "(2,"}) {
    std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': " + shape + ", }";
    header.resize(118, ' ');
    header += '\n';
    std::string file = std::string("\x93NUMPY\x01\x00", 8);
    file += char(header.size() & 0xff);
    file += char(header.size() >> 8);
    file += header + std::string(48, '\0');
    std::ofstream(dir + "/a.npy", std::ios::binary | std::ios::trunc) << file;
    INFO(shape);
    CHECK_THROWS_AS(io::read_range_npy(dir + "/a.npy"), IoError);
  }
}

TEST_CASE("a scan file too large to be a scan is refused before it is read", "[io][bad-input]") {
  const std::string dir = test::temp_dir("io_scan_huge");
  const std::string path = dir + "/000000.bin";
  std::ofstream(path, std::ios::binary).put('\0');
  fs::resize_file(path, io::kMaxScanBytes + 16);  // sparse: no disk used
  CHECK_THROWS_WITH(io::read_scan(path), Catch::Contains("000000.bin") && Catch::Contains("more than"));
}

TEST_CASE("the first NaN point of a scan is counted and indexed", "[io][bad-input]") {
  const std::string dir = test::temp_dir("io_scan_nan");
  std::vector<PointXYZI> pts(6, PointXYZI{1.f, 2.f, 3.f, 0.5f});
  pts[4].y = std::nanf("");
  pts[5].intensity = INFINITY;
  io::write_kitti_bin(dir + "/a.bin", pts);
  io::ScanReadStats st;
  CHECK(io::read_scan(dir + "/a.bin", &st).size() == 4);
  CHECK(st.non_finite == 2);
  CHECK(st.first_non_finite == 4);
}
