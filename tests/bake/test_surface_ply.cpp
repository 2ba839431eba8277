// The baked surface mesh: its vertices lie on the analytic surfaces, its PLY parses back with
// the project's reader (x y z intensity) and with a plain reader of the header, vertex records
// and triangle faces written here (what another tool reads).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "bake/surface_mesh.hpp"
#include "bake_test_scene.hpp"
#include "io/ply_reader.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;

TEST_CASE("the baked surface mesh lies on the surfaces and its PLY parses back", "[bake][ply]") {
  const bake::BakedScene s =
      bake::bake_field(test::test_scene_config(), test::test_scene_input(), test::test_scene_probe());
  const bake::SurfaceMesh m = bake::extract_surface(s, bake::surface_level(s));
  const size_t n = m.intensity.size();
  REQUIRE(n > 100);
  REQUIRE(m.triangles.size() > n);  // a connected sheet: about two triangles per vertex
  // The level σ·voxel = ln 2 sits where 2 − 25·sdf = log(ln 2 / 0.2): sdf ≈ 0.13 m behind.
  const float sdf_level = (2.0f - bake::surface_level(s)) / 25.0f;
  for (size_t p = 0; p < n; ++p) {
    const float sdf = test::test_scene_sdf(m.xyz[3 * p], m.xyz[3 * p + 1], m.xyz[3 * p + 2]);
    INFO("vertex " << p);
    CHECK(sdf == Approx(sdf_level).margin(0.1f));
    CHECK(m.drop[p] == Approx(0.15f).margin(0.11f));  // 1 − (0.85 − 0.1·|d_z|)
  }
  for (const auto& t : m.triangles)
    for (int v : t) REQUIRE((v >= 0 && size_t(v) < n));

  const std::string path = test::temp_dir("bake_ply") + "/surface.ply";
  bake::write_surface_ply(path, m);
  // The project's reader: vertices and intensity, faces skipped record by record.
  const std::vector<PointXYZI> pts = io::read_ply(path);
  REQUIRE(pts.size() == n);
  for (size_t p = 0; p < n; p += 97) {
    CHECK(pts[p].x == m.xyz[3 * p]);
    CHECK(pts[p].z == m.xyz[3 * p + 2]);
    CHECK(pts[p].intensity == m.intensity[p]);
  }
  // A plain reader: header lines, then the binary records.
  std::ifstream in(path, std::ios::binary);
  std::string line, header;
  size_t n_vertex = 0, n_face = 0;
  while (std::getline(in, line) && line != "end_header") {
    header += line + "\n";
    std::istringstream ls(line);
    std::string w, e;
    ls >> w;
    if (w == "element") {
      size_t c = 0;
      ls >> e >> c;
      (e == "vertex" ? n_vertex : n_face) = c;
    }
  }
  CHECK(header.rfind("ply\nformat binary_little_endian 1.0\n", 0) == 0);
  CHECK(header.find("property float drop_probability\n") != std::string::npos);
  CHECK(header.find("property list uchar int vertex_indices\n") != std::string::npos);
  REQUIRE(n_vertex == n);
  REQUIRE(n_face == m.triangles.size());
  std::vector<float> rec(5 * n);
  in.read(reinterpret_cast<char*>(rec.data()), std::streamsize(rec.size() * 4));
  for (size_t p = 0; p < n; p += 53) CHECK(rec[5 * p + 4] == m.drop[p]);
  for (size_t f = 0; f < n_face; ++f) {
    unsigned char cnt = 0;
    int idx[3];
    in.read(reinterpret_cast<char*>(&cnt), 1);
    in.read(reinterpret_cast<char*>(idx), 12);
    REQUIRE(cnt == 3);
    if (f % 101 == 0) CHECK(std::memcmp(idx, m.triangles[f].data(), 12) == 0);
  }
  REQUIRE(in.good());
  CHECK(in.peek() == std::char_traits<char>::eof());  // nothing after the last face
}
