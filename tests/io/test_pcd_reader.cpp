// PCD reader: writer → reader round trips for the three DATA encodings, hand-made headers with
// fields in other orders and of other types, COUNT > 1 and unknown fields skipped, v0.6
// headers, NaN points, and the LZF codec on its own.
#include <catch2/catch.hpp>

#include <cmath>

#include "io/cloud_writers.hpp"
#include "io/lzf.hpp"
#include "io/pcd_reader.hpp"
#include "scan_bytes.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;
using test::Bytes;

TEST_CASE("PCD round trip: ascii, binary, binary_compressed, with and without ring and time", "[io][pcd]") {
  const std::string dir = test::temp_dir("io_pcd_round");
  io::ScanExtras ex;
  const auto pts = test::random_scan(40, 7, &ex);
  float max_i = 0.f;
  for (const auto& p : pts) max_i = std::max(max_i, p.intensity);
  for (auto enc : {io::PcdEncoding::kAscii, io::PcdEncoding::kBinary, io::PcdEncoding::kBinaryCompressed}) {
    for (bool extras : {false, true}) {
      INFO("encoding " << int(enc) << " extras " << extras);
      const std::string path = dir + "/a" + std::to_string(int(enc)) + std::to_string(extras) + ".pcd";
      io::write_pcd(path, pts, enc, extras ? &ex : nullptr);
      io::ScanReadStats st;
      io::ScanExtras back;
      const auto got = io::read_pcd(path, &st, &back);
      CHECK(test::same_bits(got, pts));
      CHECK(st.records == pts.size());
      CHECK(st.non_finite == 0);
      CHECK(st.max_intensity == max_i);
      CHECK(back.has_intensity);
      CHECK(back.has_ring == extras);
      CHECK(back.has_time == extras);
      CHECK(back.ring == (extras ? ex.ring : std::vector<int32_t>{}));
      CHECK(back.time == (extras ? ex.time : std::vector<double>{}));
      CHECK(test::same_bits(io::read_scan(path), pts));  // dispatch by name
    }
  }
}

TEST_CASE("PCD binary_compressed of a repetitive scan is smaller than binary", "[io][pcd]") {
  const std::string dir = test::temp_dir("io_pcd_small");
  std::vector<PointXYZI> pts(500, PointXYZI{1.f, 2.f, 3.f, 0.5f});
  io::write_pcd(dir + "/b.pcd", pts, io::PcdEncoding::kBinary);
  io::write_pcd(dir + "/c.pcd", pts, io::PcdEncoding::kBinaryCompressed);
  CHECK(io::read_file_bytes(dir + "/c.pcd").size() * 4 < io::read_file_bytes(dir + "/b.pcd").size());
  CHECK(test::same_bits(io::read_pcd(dir + "/c.pcd"), pts));
}

namespace {
// FIELDS intensity x ring y z time rgb normal: U1 F8 U2 F4 I2 U4 F4 F4×3 (34 bytes a point).
const char* kMixedHeader =
    "# hand-made\nVERSION .7\nFIELDS intensity x ring y z time rgb normal\nSIZE 1 8 2 4 2 4 4 4\n"
    "TYPE U F U F I U F F\nCOUNT 1 1 1 1 1 1 1 3\nWIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\n";
struct Mixed {
  uint8_t i;
  double x;
  uint16_t ring;
  float y;
  int16_t z;
  uint32_t t;
};
const Mixed kMixed[2] = {{200, -12.5, 31, 4.25f, -7, 1000}, {3, 1e-3, 65535, -0.5f, 32767, 4000000000u}};
void check_mixed(const std::vector<PointXYZI>& p, const io::ScanExtras& ex) {
  REQUIRE(p.size() == 2);
  for (size_t k = 0; k < 2; ++k) {
    CHECK(p[k].x == float(kMixed[k].x));
    CHECK(p[k].y == kMixed[k].y);
    CHECK(p[k].z == float(kMixed[k].z));
    CHECK(p[k].intensity == float(kMixed[k].i));
    CHECK(ex.ring[k] == int32_t(kMixed[k].ring));
    CHECK(ex.time[k] == double(kMixed[k].t));
  }
}
}  // namespace

TEST_CASE("PCD fields in another order, of mixed types, COUNT 3 and unknown fields skipped", "[io][pcd]") {
  const std::string dir = test::temp_dir("io_pcd_mixed");
  Bytes bin, soa, txt;
  bin.str(kMixedHeader).str("DATA binary\n");
  txt.str(kMixedHeader).str("DATA ascii\n");
  for (const auto& m : kMixed) {
    bin.le(m.i).le(m.x).le(m.ring).le(m.y).le(m.z).le(m.t).le(9.f).le(0.1f).le(0.2f).le(0.3f);
    txt.str(std::to_string(m.i) + " " + std::to_string(m.x) + " " + std::to_string(m.ring) + " " + std::to_string(m.y) +
            " " + std::to_string(m.z) + " " + std::to_string(m.t) + " 9 0.1 0.2 0.3\n");
  }
  // binary_compressed: one block per field, each POINTS × SIZE × COUNT bytes.
  for (const auto& m : kMixed) soa.le(m.i);
  for (const auto& m : kMixed) soa.le(m.x);
  for (const auto& m : kMixed) soa.le(m.ring);
  for (const auto& m : kMixed) soa.le(m.y);
  for (const auto& m : kMixed) soa.le(m.z);
  for (const auto& m : kMixed) soa.le(m.t);
  for (int k = 0; k < 2; ++k) soa.le(9.f);
  for (int k = 0; k < 2; ++k) soa.le(0.1f).le(0.2f).le(0.3f);
  const auto z = io::lzf_compress(reinterpret_cast<const uint8_t*>(soa.s.data()), soa.s.size());
  Bytes cmp;
  cmp.str(kMixedHeader).str("DATA binary_compressed\n").le(uint32_t(z.size())).le(uint32_t(soa.s.size()));
  cmp.s.append(reinterpret_cast<const char*>(z.data()), z.size());
  const std::pair<const char*, const Bytes*> files[] = {{"bin", &bin}, {"txt", &txt}, {"cmp", &cmp}};
  for (const auto& [name, b] : files) {
    INFO(name);
    b->write(dir + "/" + name + ".pcd");
    io::ScanExtras ex;
    io::ScanReadStats st;
    const auto p = io::read_pcd(dir + "/" + name + ".pcd", &st, &ex);
    check_mixed(p, ex);
    CHECK(st.max_intensity == 200.f);  // a 0–255 sensor: reported, not rescaled
  }
}

TEST_CASE("PCD v0.6 header (no VERSION, POINTS, COUNT), CRLF lines, organised cloud with NaN points", "[io][pcd]") {
  const std::string dir = test::temp_dir("io_pcd_v06");
  Bytes b;
  b.str("FIELDS x y z\r\nSIZE 4 4 4\r\nTYPE F F F\r\nWIDTH 2\r\nHEIGHT 2\r\nDATA ascii\r\n");
  b.str("1 2 3\r\nnan nan nan\r\n4 5 6\r\n7 8 inf\r\n");
  b.write(dir + "/o.pcd");
  io::ScanReadStats st;
  io::ScanExtras ex;
  const auto p = io::read_pcd(dir + "/o.pcd", &st, &ex);
  REQUIRE(p.size() == 2);
  CHECK(p[1].x == 4.f);
  CHECK(p[1].intensity == 0.f);
  CHECK(st.records == 4);
  CHECK(st.non_finite == 2);
  CHECK(st.first_non_finite == 1);
  CHECK(st.max_intensity == 0.f);
  CHECK_FALSE(ex.has_intensity);
  CHECK_FALSE(ex.has_ring);
}

TEST_CASE("PCD intensity aliases: reflectance, i; timestamp and t", "[io][pcd]") {
  const std::string dir = test::temp_dir("io_pcd_alias");
  for (const std::string names : {"x y z reflectance t", "X Y Z i timestamp"}) {
    INFO(names);
    Bytes b;
    b.str("FIELDS " + names + "\nSIZE 4 4 4 4 8\nTYPE F F F F F\nCOUNT 1 1 1 1 1\nWIDTH 1\nPOINTS 1\nDATA ascii\n");
    b.str("1 2 3 0.5 12.25\n");
    b.write(dir + "/a.pcd");
    io::ScanExtras ex;
    const auto p = io::read_pcd(dir + "/a.pcd", nullptr, &ex);
    REQUIRE(p.size() == 1);
    CHECK(p[0].intensity == 0.5f);
    REQUIRE(ex.has_time);
    CHECK(ex.time[0] == 12.25);
  }
}

TEST_CASE("LZF: round trips, sizes, corrupt streams refused", "[io][pcd][lzf]") {
  Rng rng(11);
  std::vector<uint8_t> noise(5000), zeros(70000, 0), pattern(3000);
  for (auto& v : noise) v = uint8_t(rng.next_u32());
  for (size_t k = 0; k < pattern.size(); ++k) pattern[k] = uint8_t("abcabcabd"[k % 9]);
  for (const auto* in : {&noise, &zeros, &pattern}) {
    const auto z = io::lzf_compress(in->data(), in->size());
    std::vector<uint8_t> out(in->size());
    std::string err;
    size_t off = 0;
    REQUIRE(io::lzf_decompress(z.data(), z.size(), out.data(), out.size(), err, off));
    CHECK(out == *in);
    CHECK(z.size() <= in->size() + in->size() / 32 + 1);
    CHECK(in->size() <= z.size() * io::kLzfMaxRatio);
  }
  CHECK(io::lzf_compress(zeros.data(), zeros.size()).size() < 1000);
  std::vector<uint8_t> out(16);
  std::string err;
  size_t off = 0;
  const uint8_t cut_literal[] = {5, 'a', 'b'};  // 6 literal bytes announced, 2 present
  CHECK_FALSE(io::lzf_decompress(cut_literal, 3, out.data(), 6, err, off));
  CHECK(err.find("literal") != std::string::npos);
  const uint8_t early_ref[] = {0, 'a', 0x20, 0x05};  // reference 6 bytes back after 1 byte
  CHECK_FALSE(io::lzf_decompress(early_ref, 4, out.data(), 4, err, off));
  CHECK(off == 2);
  const uint8_t ok[] = {1, 'a', 'b', 0x20, 0x01};  // "ab" then 3 bytes from 2 back: "ababa"
  CHECK(io::lzf_decompress(ok, 5, out.data(), 5, err, off));
  CHECK(std::string(out.begin(), out.begin() + 5) == "ababa");
  CHECK_FALSE(io::lzf_decompress(ok, 5, out.data(), 4, err, off));  // overflows 4 bytes
  CHECK_FALSE(io::lzf_decompress(ok, 5, out.data(), 6, err, off));  // ends short of 6
  CHECK_FALSE(io::lzf_decompress(ok, 4, out.data(), 5, err, off));  // reference cut off
}
