// PLY reader: writer → reader round trips for ascii and both binary byte orders, hand-made
// files with faces (list properties) before and after the vertices, list properties inside
// the vertex element, big-endian doubles, and every property type name.
#include <catch2/catch.hpp>

#include "io/cloud_writers.hpp"
#include "io/ply_reader.hpp"
#include "scan_bytes.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;
using test::Bytes;

TEST_CASE("PLY round trip: ascii, binary little and big endian, with and without ring and time", "[io][ply]") {
  const std::string dir = test::temp_dir("io_ply_round");
  io::ScanExtras ex;
  const auto pts = test::random_scan(40, 9, &ex);
  for (auto enc : {io::PlyEncoding::kAscii, io::PlyEncoding::kBinaryLittleEndian, io::PlyEncoding::kBinaryBigEndian}) {
    for (bool extras : {false, true}) {
      INFO("encoding " << int(enc) << " extras " << extras);
      const std::string path = dir + "/a" + std::to_string(int(enc)) + std::to_string(extras) + ".ply";
      io::write_ply(path, pts, enc, extras ? &ex : nullptr);
      io::ScanReadStats st;
      io::ScanExtras back;
      const auto got = io::read_ply(path, &st, &back);
      CHECK(test::same_bits(got, pts));
      CHECK(st.records == pts.size());
      CHECK(back.has_ring == extras);
      CHECK(back.has_time == extras);
      CHECK(back.ring == (extras ? ex.ring : std::vector<int32_t>{}));
      CHECK(back.time == (extras ? ex.time : std::vector<double>{}));
      CHECK(test::same_bits(io::read_scan(path), pts));  // dispatch by name
    }
  }
}

TEST_CASE("PLY binary: a face element before the vertices, lists inside them, an element after", "[io][ply]") {
  const std::string dir = test::temp_dir("io_ply_faces");
  Bytes b;
  b.str("ply\nformat binary_little_endian 1.0\ncomment made by hand\nobj_info scanner 7\n"
        "element face 2\nproperty list uchar int vertex_indices\nproperty uchar flags\n"
        "element vertex 3\nproperty double x\nproperty uint8 intensity\nproperty float y\n"
        "property list ushort float normals\nproperty short z\nproperty ushort ring\nproperty double timestamp\n"
        "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n");
  b.le(uint8_t(3)).le(int32_t(0)).le(int32_t(1)).le(int32_t(2)).le(uint8_t(1));  // face 0: 3 indices
  b.le(uint8_t(0)).le(uint8_t(2));                                               // face 1: empty list
  for (int k = 0; k < 3; ++k) {
    b.le(double(k) + 0.5).le(uint8_t(100 + k)).le(float(-k)).le(uint16_t(k));
    for (int n = 0; n < k; ++n) b.le(float(n));  // k normals
    b.le(int16_t(-300 * k)).le(uint16_t(10 + k)).le(1.5e9 + k * 0.1);
  }
  b.le(int32_t(0)).le(int32_t(1));
  b.write(dir + "/f.ply");
  io::ScanExtras ex;
  io::ScanReadStats st;
  const auto p = io::read_ply(dir + "/f.ply", &st, &ex);
  REQUIRE(p.size() == 3);
  for (int k = 0; k < 3; ++k) {
    CHECK(p[size_t(k)].x == float(k + 0.5));
    CHECK(p[size_t(k)].y == float(-k));
    CHECK(p[size_t(k)].z == float(-300 * k));
    CHECK(p[size_t(k)].intensity == float(100 + k));
    CHECK(ex.ring[size_t(k)] == 10 + k);
    CHECK(ex.time[size_t(k)] == 1.5e9 + k * 0.1);
  }
  CHECK(st.max_intensity == 102.f);
}

TEST_CASE("PLY big-endian doubles and every property type name", "[io][ply]") {
  const std::string dir = test::temp_dir("io_ply_be");
  Bytes b;
  b.str("ply\nformat binary_big_endian 1.0\nelement vertex 2\nproperty float64 x\nproperty double y\n"
        "property double z\nproperty float32 reflectance\nproperty char c\nproperty int8 c8\n"
        "property short s\nproperty int16 s16\nproperty uint u\nproperty uint32 u32\nproperty int32 ring\n"
        "property float t\nend_header\n");
  for (int k = 0; k < 2; ++k)
    b.be(123456.789 * (k + 1)).be(-2.0e-7).be(k ? 1e300 : 4.0).be(0.75f).be(int8_t(-1)).be(int8_t(2)).be(int16_t(3))
        .be(int16_t(4)).be(uint32_t(5)).be(uint32_t(6)).be(int32_t(-70000)).be(0.25f);
  b.write(dir + "/be.ply");
  io::ScanExtras ex;
  io::ScanReadStats st;
  const auto p = io::read_ply(dir + "/be.ply", &st, &ex);
  REQUIRE(p.size() == 1);  // z = 1e300 does not fit a float: dropped as non-finite
  CHECK(st.non_finite == 1);
  CHECK(st.first_non_finite == 1);
  CHECK(p[0].x == float(123456.789));
  CHECK(p[0].y == float(-2.0e-7));
  CHECK(p[0].z == 4.f);
  CHECK(p[0].intensity == 0.75f);
  CHECK(ex.ring == std::vector<int32_t>{-70000});
  CHECK(ex.time == std::vector<double>{0.25});
}

TEST_CASE("PLY ascii: faces before and after the vertices, scalar_intensity, CRLF", "[io][ply]") {
  const std::string dir = test::temp_dir("io_ply_ascii");
  Bytes b;
  b.str("ply\r\nformat ascii 1.0\r\nelement face 1\r\nproperty list uchar uint vertex_index\r\n"
        "element vertex 2\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\n"
        "property uchar scalar_intensity\r\nproperty list int int idx\r\nelement face2 1\r\n"
        "property list uint8 int32 vertex_index\r\nend_header\r\n");
  b.str("4 0 1 2 3\r\n1.5 -2 3e1 255 2 7 8\r\n4 5 6 0 0\r\n3 1 1 1\r\n");
  b.write(dir + "/a.ply");
  io::ScanExtras ex;
  io::ScanReadStats st;
  const auto p = io::read_ply(dir + "/a.ply", &st, &ex);
  REQUIRE(p.size() == 2);
  CHECK(p[0].x == 1.5f);
  CHECK(p[0].z == 30.f);
  CHECK(p[0].intensity == 255.f);
  CHECK(p[1].y == 5.f);
  CHECK(st.max_intensity == 255.f);
  CHECK(ex.has_intensity);
  CHECK_FALSE(ex.has_time);
}
