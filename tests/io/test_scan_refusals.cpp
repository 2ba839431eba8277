// Bad PCD and PLY files, one per kind of mistake: each is refused with an IoError whose message
// names the file, a byte offset and what was wrong; claims of huge sizes are refused before
// anything of that size is allocated.
#include <catch2/catch.hpp>

#include "io/lzf.hpp"
#include "io/pcd_reader.hpp"
#include "io/ply_reader.hpp"
#include "scan_bytes.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;
using test::Bytes;

namespace {
std::string pcd_head(const std::string& fields, const std::string& size, const std::string& type,
                     const std::string& points, const std::string& data) {
  return "VERSION 0.7\nFIELDS " + fields + "\nSIZE " + size + "\nTYPE " + type + "\nWIDTH " + points +
         "\nHEIGHT 1\nPOINTS " + points + "\nDATA " + data + "\n";
}
void expect_refusal(const std::string& path, const std::string& what, bool ply) {
  const std::string m = test::refusal([&] { ply ? io::read_ply(path) : io::read_pcd(path); });
  INFO(path << " -> " << m);
  CHECK(m.find(path) != std::string::npos);
  CHECK(m.find("byte offset") != std::string::npos);
  CHECK(m.find(what) != std::string::npos);
}
}  // namespace

TEST_CASE("PCD refusals name the file, the offset and the mistake", "[io][pcd][bad-input]") {
  const std::string dir = test::temp_dir("io_pcd_bad");
  const std::string xyz = pcd_head("x y z", "4 4 4", "F F F", "2", "binary");
  const std::string two(24, '\0');
  struct Case { const char* name; std::string bytes; const char* what; };
  const uint8_t bad_ref[] = {0x20, 0x05};  // a reference before the first output byte
  const Case cases[] = {
      {"no_z", pcd_head("x y intensity", "4 4 4", "F F F", "2", "binary") + two, "no field z"},
      {"size_count", pcd_head("x y z", "4 4", "F F F", "2", "binary") + two, "SIZE has 2 values for 3 FIELDS"},
      {"size_type", pcd_head("x y z", "4 3 4", "F F F", "2", "binary") + two, "SIZE 3 does not fit TYPE 'F'"},
      {"f2", pcd_head("x y z", "4 2 4", "F F F", "2", "binary") + two, "does not fit TYPE"},
      {"points_wh", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 3\nHEIGHT 2\nPOINTS 5\nDATA binary\n", "is not WIDTH 3 x HEIGHT 2"},
      {"truncated", xyz + std::string(20, '\0'), "truncated"},
      {"trailing", xyz + two + "x", "1 bytes after the last"},
      {"huge_points", pcd_head("x y z", "4 4 4", "F F F", "4000000000", "binary") + two, "truncated"},
      {"no_data", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\n", "without a DATA line"},
      {"unknown_key", "FIELDS x y z\nSHAPE 2\nDATA ascii\n", "unknown key 'SHAPE'"},
      {"twice", pcd_head("x y z x", "4 4 4 4", "F F F F", "1", "ascii") + "1 2 3 4\n", "'x' appears twice"},
      {"count_x", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 2 1 1\nWIDTH 1\nDATA ascii\n1 1 2 3\n", "COUNT 2; it must be 1"},
      {"empty", pcd_head("x y z", "4 4 4", "F F F", "0", "binary"), "empty scan"},
      {"data_kind", pcd_head("x y z", "4 4 4", "F F F", "1", "binary_lzma"), "not ascii, binary or binary_compressed"},
      {"ascii_count", pcd_head("x y z", "4 4 4", "F F F", "2", "ascii") + "1 2 3\n1 2\n", "2 values"},
      {"ascii_type", pcd_head("x y z ring", "4 4 4 1", "F F F U", "1", "ascii") + "1 2 3 300\n", "'300' is not a value"},
      {"ascii_short", pcd_head("x y z", "4 4 4", "F F F", "3", "ascii") + "1 2 3\n", "truncated: 1 of POINTS 3"},
      {"ascii_long", pcd_head("x y z", "4 4 4", "F F F", "1", "ascii") + "1 2 3\n4 5 6\n", "more points than POINTS"},
      {"ring_range", pcd_head("x y z ring", "4 4 4 8", "F F F F", "1", "ascii") + "1 2 3 1e12\n", "outside int32"},
      {"lzf_corrupt",
       pcd_head("x y z", "4 4 4", "F F F", "1", "binary_compressed") + Bytes().le(uint32_t(2)).le(uint32_t(12)).s +
           std::string(reinterpret_cast<const char*>(bad_ref), 2),
       "LZF stream corrupt"},
      {"lzf_ratio", pcd_head("x y z", "4 4 4", "F F F", "1000000", "binary_compressed") +
                        Bytes().le(uint32_t(2)).le(uint32_t(12000000)).s + "ab",
       "cannot hold"},
      {"lzf_usize", pcd_head("x y z", "4 4 4", "F F F", "2", "binary_compressed") + Bytes().le(uint32_t(2)).le(uint32_t(25)).s + "ab",
       "uncompressed size 25 is not POINTS 2"},
      {"lzf_short", pcd_head("x y z", "4 4 4", "F F F", "2", "binary_compressed") + "abc", "needs 8 size bytes"},
      {"lzf_cut", pcd_head("x y z", "4 4 4", "F F F", "2", "binary_compressed") + Bytes().le(uint32_t(40)).le(uint32_t(24)).s + "ab",
       "truncated: compressed size 40"},
  };
  for (const auto& c : cases) {
    const std::string path = dir + "/" + c.name + ".pcd";
    io::write_file_bytes(path, c.bytes.data(), c.bytes.size());
    expect_refusal(path, c.what, false);
  }
  // A header error names its line (TYPE, the 4th, where SIZE 3 meets F).
  const std::string m = test::refusal([&] { io::read_pcd(dir + "/size_type.pcd"); });
  CHECK(m.find("header line 4") != std::string::npos);
}

TEST_CASE("PLY refusals name the file, the offset and the mistake", "[io][ply][bad-input]") {
  const std::string dir = test::temp_dir("io_ply_bad");
  const std::string head = "ply\nformat binary_little_endian 1.0\n";
  const std::string vtx = "element vertex 2\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string two(24, '\0');
  struct Case { const char* name; std::string bytes; const char* what; };
  const Case cases[] = {
      {"magic", "plx\nformat ascii 1.0\n", "not a PLY file"},
      {"format", "ply\nformat binary 1.0\n" + vtx + "end_header\n", "is not ascii, binary_little_endian"},
      {"no_format", "ply\n" + vtx + "end_header\n" + two, "no format line"},
      {"no_vertex", head + "element face 0\nproperty list uchar int v\nend_header\n", "no vertex element"},
      {"no_y", head + "element vertex 1\nproperty float x\nproperty float z\nend_header\n" + two, "no property y"},
      {"type", head + "element vertex 1\nproperty float x\nproperty real y\nproperty float z\nend_header\n", "unknown property type 'real'"},
      {"list_float", head + "element face 1\nproperty list float int v\n" + vtx + "end_header\n", "not an integer type"},
      {"list_xyz", head + "element vertex 1\nproperty float x\nproperty list uchar float y\nproperty float z\nend_header\n", "is a list"},
      {"keyword", head + vtx + "elements 3\nend_header\n", "unknown keyword 'elements'"},
      {"prop_first", head + "property float x\n" + vtx + "end_header\n", "property before any element"},
      {"no_end", head + vtx, "without end_header"},
      {"truncated", head + vtx + "end_header\n" + std::string(20, '\0'), "truncated"},
      {"huge", head + "element vertex 4000000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n" + two, "truncated"},
      {"face_cut", head + "element face 1\nproperty list uchar int v\n" + vtx + "end_header\n" + Bytes().le(uint8_t(9)).le(int32_t(1)).s,
       "truncated: list count 9"},
      {"face_neg", head + "element face 1\nproperty list int int v\n" + vtx + "end_header\n" + Bytes().le(int32_t(-2)).s + two,
       "negative list count -2"},
      {"trailing", head + vtx + "end_header\n" + two + "zz", "2 bytes after the last element"},
      {"empty", head + "element vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n", "empty scan"},
      {"ascii_token", "ply\nformat ascii 1.0\n" + vtx + "end_header\n1 2 3\n4 five 6\n", "'five' is not a value"},
      {"ascii_short", "ply\nformat ascii 1.0\n" + vtx + "end_header\n1 2 3\n4 5\n", "property z missing"},
      {"ascii_long", "ply\nformat ascii 1.0\n" + vtx + "end_header\n1 2 3\n4 5 6\n7\n", "data after the last element"},
      {"ascii_list", "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int v\n" + vtx + "end_header\n300 1\n",
       "'300' is not a value"},
  };
  for (const auto& c : cases) {
    const std::string path = dir + "/" + c.name + ".ply";
    io::write_file_bytes(path, c.bytes.data(), c.bytes.size());
    expect_refusal(path, c.what, true);
  }
  const std::string m = test::refusal([&] { io::read_ply(dir + "/type.ply"); });
  CHECK(m.find("header line 5") != std::string::npos);
}

TEST_CASE("read_scan picks the reader by name and refuses other names", "[io][bad-input]") {
  const std::string dir = test::temp_dir("io_scan_names");
  CHECK(io::is_scan_file("a.pcd"));
  CHECK(io::is_scan_file("a.ply"));
  CHECK(io::is_scan_file("a.pcd.bin"));
  CHECK_FALSE(io::is_scan_file("a.las"));
  const std::string m = test::refusal([&] { io::read_scan(dir + "/a.las"); });
  CHECK(m.find(".pcd or .ply") != std::string::npos);
  // nuScenes through read_scan: its rings come back as ScanExtras.
  test::Bytes nus;
  nus.le(1.f).le(2.f).le(3.f).le(51.f).le(7.f).le(4.f).le(5.f).le(6.f).le(255.f).le(31.f);
  nus.write(dir + "/n.pcd.bin");
  io::ScanExtras ex;
  io::ScanReadStats st;
  REQUIRE(io::read_scan(dir + "/n.pcd.bin", &st, &ex).size() == 2);
  CHECK(ex.has_ring);
  CHECK(ex.ring == std::vector<int32_t>{7, 31});
  CHECK_FALSE(ex.has_time);
  CHECK(st.max_intensity == Approx(1.0));
}
