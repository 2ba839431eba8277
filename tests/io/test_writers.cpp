// Writers: PLY, PCD, PNG pictures, the .npy range-image format.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "core/error.hpp"
#include "io/cloud_writers.hpp"
#include "io/marked_depth_picture.hpp"
#include "io/png_writer.hpp"
#include "io/range_array.hpp"
#include "io/scan_io.hpp"
#include "io/trajectory_svg.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;

TEST_CASE("PLY and PCD: header then packed float32 x y z intensity", "[io]") {
  const std::string dir = test::temp_dir("io_clouds");
  const std::vector<PointXYZI> pts = {{1, 2, 3, 0.5f}, {4, 5, 6, 0.75f}, {7, 8, 9, 1.f}};
  io::write_ply(dir + "/a.ply", pts);
  io::write_pcd(dir + "/a.pcd", pts);
  for (const std::string f : {"/a.ply", "/a.pcd"}) {
    const auto b = io::read_file_bytes(dir + f);
    const std::string s(b.begin(), b.end());
    const std::string end_marker = f == "/a.ply" ? "end_header\n" : "DATA binary\n";
    const size_t h = s.find(end_marker);
    REQUIRE(h != std::string::npos);
    REQUIRE(b.size() == h + end_marker.size() + 3 * 16);
    float v[4];
    std::memcpy(v, b.data() + h + end_marker.size() + 16, 16);
    CHECK(v[0] == 4.f);
    CHECK(v[3] == 0.75f);
    CHECK(s.find(f == "/a.ply" ? "element vertex 3" : "POINTS 3") != std::string::npos);
  }
}

TEST_CASE("write_ply(path, pts) and write_pcd(path, pts): their bytes are pinned", "[io]") {
  // Literal headers as these two writers have always written them, then the packed floats:
  // the extended writers they now delegate to must not change a byte of them.
  const std::string dir = test::temp_dir("io_clouds_pinned");
  const std::vector<PointXYZI> pts = {{1, -2, 3.25f, 0.5f}, {1e-7f, 5e6f, -6, 255.f}};
  std::string body(pts.size() * 16, '\0');
  std::memcpy(&body[0], pts.data(), body.size());
  const std::string ply = "ply\nformat binary_little_endian 1.0\ncomment sgnlf\nelement vertex 2\nproperty float x\n"
                          "property float y\nproperty float z\nproperty float intensity\nend_header\n";
  const std::string pcd = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity\n"
                          "SIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\n"
                          "POINTS 2\nDATA binary\n";
  io::write_ply(dir + "/a.ply", pts);
  io::write_pcd(dir + "/a.pcd", pts);
  const auto a = io::read_file_bytes(dir + "/a.ply"), b = io::read_file_bytes(dir + "/a.pcd");
  CHECK(std::string(a.begin(), a.end()) == ply + body);
  CHECK(std::string(b.begin(), b.end()) == pcd + body);
}

TEST_CASE("npy range image round trip and bad files", "[io]") {
  const std::string dir = test::temp_dir("io_npy");
  RangeImage img(3, 5);
  for (size_t i = 0; i < img.size(); ++i) {
    img.range[i] = float(i) * 1.5f;
    img.intensity[i] = float(i) / 20.f;
    img.ray_drop[i] = i % 2 ? 1.f : 0.f;
  }
  io::write_range_npy(dir + "/r.npy", img);
  const auto b = io::read_file_bytes(dir + "/r.npy");
  CHECK((b.size() - 15 * 12) % 64 == 0);  // header padded to 64 bytes as NumPy does
  const auto back = io::read_range_npy(dir + "/r.npy");
  CHECK(back.height == 3);
  CHECK(back.width == 5);
  CHECK(back.range == img.range);
  CHECK(back.intensity == img.intensity);
  CHECK(back.ray_drop == img.ray_drop);
  io::write_file_bytes(dir + "/cut.npy", b.data(), b.size() - 4);
  CHECK_THROWS_AS(io::read_range_npy(dir + "/cut.npy"), IoError);
  io::write_file_bytes(dir + "/bad.npy", "hello world", 11);
  CHECK_THROWS_WITH(io::read_range_npy(dir + "/bad.npy"), Catch::Contains("bad magic"));
}

TEST_CASE("npy float image: shape (H, W), the values in row order, a wrong count refused", "[io]") {
  const std::string dir = test::temp_dir("io_npy_float");
  std::vector<float> v(2 * 3);
  for (size_t i = 0; i < v.size(); ++i) v[i] = 0.25f * float(i) - 0.5f;
  io::write_float_npy(dir + "/o.npy", 2, 3, v);
  const auto b = io::read_file_bytes(dir + "/o.npy");
  REQUIRE(b.size() > 6 * 4);
  CHECK((b.size() - 6 * 4) % 64 == 0);
  const std::string header(b.begin(), b.end() - 6 * 4);
  CHECK(header.find("'shape': (2, 3)") != std::string::npos);
  CHECK(header.find("'<f4'") != std::string::npos);
  std::vector<float> back(6);
  std::memcpy(back.data(), b.data() + b.size() - 6 * 4, 6 * 4);
  CHECK(back == v);
  CHECK_THROWS_WITH(io::write_float_npy(dir + "/x.npy", 2, 4, v), Catch::Contains("6 values"));
}

TEST_CASE("PNG range picture: three stacked panels, turbo colormap", "[io]") {
  const auto lo = io::turbo(0.1), hi = io::turbo(0.9), mid = io::turbo(0.5);
  CHECK(int(lo[2]) > int(lo[0]) + 100);  // blue end
  CHECK(int(hi[0]) > int(hi[2]) + 100);  // red end
  CHECK(int(mid[1]) > 200);        // bright green-yellow middle
  RangeImage img(4, 6);
  img.range[img.idx(1, 2)] = 10.f;
  img.intensity[img.idx(1, 2)] = 1.f;
  img.ray_drop[img.idx(1, 2)] = 1.f;
  io::RangePictureOptions o;
  o.row_repeat = 2;
  o.gap = 1;
  const auto pic = io::range_image_picture(img, o);
  CHECK(pic.height == 3 * 8 + 2);
  CHECK(pic.width == 6);
  auto px = [&](int y, int x, int c) { return int(pic.rgb[(size_t(y) * pic.width + x) * 3 + c]); };
  CHECK(px(2, 2, 0) + px(2, 2, 1) + px(2, 2, 2) > 0);  // depth colour at the return
  CHECK(px(2, 3, 0) + px(2, 3, 1) + px(2, 3, 2) == 0);  // no return: black
  CHECK(px(8 + 1 + 3, 2, 0) == 255);                    // intensity 1 → white
  CHECK(px(2 * 9 + 2, 2, 1) == 255);                    // mask
  CHECK(px(2 * 9 + 2, 3, 1) == 0);
  const std::string dir = test::temp_dir("io_png");
  io::write_png(dir + "/p.png", pic);
  const auto b = io::read_file_bytes(dir + "/p.png");
  REQUIRE(b.size() > 24);
  CHECK(std::memcmp(b.data(), "\x89PNG\r\n\x1a\n", 8) == 0);
  CHECK(uint8_t(b[19]) == 6);   // IHDR width (big-endian)
  CHECK(uint8_t(b[23]) == 26);  // IHDR height
}

TEST_CASE("marked depth picture: panels stacked, false and missed returns coloured", "[io]") {
  RangeImage pred(2, 3), gt(2, 3);
  pred.range[pred.idx(0, 0)] = 5.f;   // a return with its depth colour
  pred.range[pred.idx(0, 1)] = 30.f;  // a false return
  gt.range[gt.idx(0, 0)] = 5.f;
  gt.range[gt.idx(1, 2)] = 12.f;      // missed by the prediction
  io::DepthPanel top{&pred, std::vector<uint8_t>(6, io::kMarkNone)};
  top.marks[pred.idx(0, 1)] = io::kMarkFalseReturn;
  top.marks[pred.idx(1, 2)] = io::kMarkMissedReturn;
  io::RangePictureOptions o;
  o.row_repeat = 2;
  o.gap = 1;
  const auto pic = io::marked_depth_picture({top, io::DepthPanel{&gt, {}}}, o);
  CHECK(pic.height == 2 * 4 + 1);
  CHECK(pic.width == 3);
  auto px = [&](int y, int x) {
    const uint8_t* p = &pic.rgb[(size_t(y) * pic.width + x) * 3];
    return std::array<uint8_t, 3>{p[0], p[1], p[2]};
  };
  CHECK(px(0, 0) == io::depth_colour(5.0, o));
  CHECK(px(1, 1) == io::kFalseReturnColour);
  CHECK(px(3, 2) == io::kMissedReturnColour);
  CHECK(px(2, 0) == std::array<uint8_t, 3>{0, 0, 0});   // no return, no mark
  CHECK(px(4, 1) == std::array<uint8_t, 3>{0, 0, 0});   // the gap
  CHECK(px(5 + 2, 2) == io::depth_colour(12.0, o));     // the ground truth, unmarked
  RangeImage other(3, 3);
  CHECK_THROWS_WITH(io::marked_depth_picture({top, io::DepthPanel{&other, {}}}, o),
                    Catch::Contains("panel 1 is 3x3, panel 0 2x3"));
  CHECK_THROWS_WITH(io::marked_depth_picture({io::DepthPanel{&gt, {1, 2}}}, o),
                    Catch::Contains("2 marks for 6 pixels"));
}

TEST_CASE("trajectory SVG: one polyline per trajectory, links, errors", "[io][svg]") {
  const std::string dir = test::temp_dir("io_svg");
  std::vector<Pose> a, b;
  for (int k = 0; k < 5; ++k) {
    Pose T = Pose::Identity();
    T.translation() = Vec3(2.0 * k, 0.5 * k, 0);
    a.push_back(T);
    T.translation().y() += 1.0;
    b.push_back(T);
  }
  io::write_trajectory_svg(dir + "/t.svg", "test", {{"gt", "#000", a}, {"est", "#f00", b}}, {{0, 1}});
  std::ifstream f(dir + "/t.svg");
  const std::string s((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  auto count = [&](const std::string& what) {
    size_t n = 0;
    for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
    return n;
  };
  CHECK(count("<polyline") == 2);
  CHECK(count("<circle") == 10);
  CHECK(count("stroke=\"#bbb\"") == 5);
  CHECK(s.find("est") != std::string::npos);
  std::vector<Pose> bad = a;
  bad[2].translation().x() = std::nan("");
  CHECK_THROWS_WITH(io::write_trajectory_svg(dir + "/bad.svg", "t", {{"x", "#000", bad}}),
                    Catch::Contains("pose 2 is not finite"));
  CHECK_THROWS_AS(io::write_trajectory_svg(dir + "/t2.svg", "t", {{"gt", "#000", a}, {"s", "#000", {a[0]}}}, {{0, 1}}),
                  Error);
  CHECK_THROWS_AS(io::write_trajectory_svg("/nonexistent-dir/x.svg", "t", {{"gt", "#000", a}}), IoError);
}
