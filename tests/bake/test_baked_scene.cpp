// The baked scene on the host: the bake from an analytic field (bricks only near the surfaces,
// vertex values equal to the probes'), the file round trip, refused input, the config's JSON.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include "bake/bake.hpp"
#include "bake_test_scene.hpp"
#include "core/error.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;

TEST_CASE("bake_field keeps bricks near the surfaces and stores the probes' values", "[bake]") {
  bake::BakeStats st;
  const bake::BakedScene s =
      bake::bake_field(test::test_scene_config(), test::test_scene_input(), test::test_scene_probe(), &st);
  s.validate();
  CHECK(st.kept_bricks > 50);
  CHECK(st.kept_bricks <= st.candidate_bricks);
  CHECK(long(s.bricks()) == st.kept_bricks);
  CHECK(st.head_rows == long(s.vertices.size()));
  const auto probe = test::test_scene_probe();
  const int n1 = s.brick + 1;
  long checked = 0;
  for (int k = 0; k < s.dims[2]; ++k)
    for (int j = 0; j < s.dims[1]; ++j)
      for (int i = 0; i < s.dims[0]; ++i) {
        const int slot = s.index[size_t((k * s.dims[1] + j) * s.dims[0] + i)];
        if (slot < 0) continue;
        // Every stored brick lies within a brick and the dilation of a surface.
        const auto c = s.vertex_position({i, j, k}, s.brick / 2, s.brick / 2, s.brick / 2);
        CHECK(std::fabs(test::test_scene_sdf(float(c[0]), float(c[1]), float(c[2]))) <
              float(s.brick_m()) + 0.3f);
        // A corner vertex holds the density probe's value there.
        const auto p = s.vertex_position({i, j, k}, 1, 2, 3);
        const std::vector<float> x{float(p[0]), float(p[1]), float(p[2])};
        const float want = probe.density(x, 1)[0];
        CHECK(s.vertices[size_t(slot) * size_t(s.vertices_per_brick()) + size_t((3 * n1 + 2) * n1 + 1)].logit ==
              Approx(want).margin(1e-5));
        ++checked;
      }
  CHECK(checked == st.kept_bricks);
}

TEST_CASE("a baked scene's file reads back bit for bit; bad files are refused", "[bake]") {
  bake::BakedScene s =
      bake::bake_field(test::test_scene_config(), test::test_scene_input(), test::test_scene_probe());
  s.provenance = Json{{"run", "test"}};
  const std::string dir = test::temp_dir("bake_file");
  const std::string path = dir + "/scene.bake";
  bake::write_baked_scene(path, s);
  const bake::BakedScene r = bake::read_baked_scene(path);
  CHECK(r.dims == s.dims);
  CHECK(r.origin_m == s.origin_m);
  CHECK(r.index == s.index);
  REQUIRE(r.vertices.size() == s.vertices.size());
  CHECK(std::memcmp(r.vertices.data(), s.vertices.data(), s.vertices.size() * sizeof(bake::BakedVertex)) == 0);
  CHECK(r.step_m == s.step_m);
  CHECK(r.provenance == s.provenance);
  // Not a baked scene; truncated.
  {
    std::ofstream(dir + "/bad.bake") << "hello";
  }
  CHECK_THROWS_AS(bake::read_baked_scene(dir + "/bad.bake"), IoError);
  {
    std::ifstream in(path, std::ios::binary);
    std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(dir + "/short.bake", std::ios::binary) << all.substr(0, all.size() - 100);
  }
  CHECK_THROWS_WITH(bake::read_baked_scene(dir + "/short.bake"), Catch::Contains("truncated"));
  CHECK_THROWS_AS(bake::read_baked_scene(dir + "/missing.bake"), IoError);
  // A slot outside the vertices.
  bake::BakedScene bad = s;
  bad.index[0] = int32_t(bad.bricks());
  CHECK_THROWS_AS(bad.validate(), NumericError);
}

TEST_CASE("the bake config reads JSON strictly", "[bake]") {
  const bake::BakeConfig c = bake::BakeConfig::from_json(Json{{"voxel_m", 0.05}, {"brick", 4}}, "t");
  CHECK(c.voxel_m == Approx(0.05f));
  CHECK(c.brick == 4);
  CHECK(c.step() == Approx(0.05f));
  CHECK_THROWS_AS(bake::BakeConfig::from_json(Json{{"voxel", 0.05}}, "t"), ConfigError);
  CHECK_THROWS_AS(bake::BakeConfig::from_json(Json{{"brick", 1}}, "t"), ConfigError);
  CHECK_THROWS_AS(bake::BakeConfig::from_json(Json{{"step_m", 0.5}, {"voxel_m", 0.1}}, "t"), ConfigError);
  CHECK(bake::BakeConfig::from_json(c.to_json(), "t").to_json() == c.to_json());
  bake::BakeInput none;
  CHECK_THROWS_AS(bake::bake_field(c, none, test::test_scene_probe()), ConfigError);
}
