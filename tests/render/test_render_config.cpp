// RenderConfig: presets, validation and strict JSON.
#include <catch2/catch.hpp>

#include "core/config.hpp"
#include "render/render_config.hpp"

using namespace sgnlf;

TEST_CASE("Render config presets, JSON round trip and rejection of bad values",
          "[render][config]") {
  const auto k = render::RenderConfig::preset("kitti360");
  CHECK(k.weights.depth == 1000.f);
  CHECK(k.weights.ret == 1.f);
  CHECK(k.weights.intensity == 10.f);
  const auto n = render::RenderConfig::preset("nuscenes");
  CHECK(n.weights.ret == 4.5f);
  CHECK(n.weights.intensity == 100.f);
  CHECK_THROWS_AS(render::RenderConfig::preset("waymo"), ConfigError);

  auto c = k;
  c.n_samples = 96;
  c.n_importance = 16;
  c.weights.grad = 50.f;
  const auto back = render::RenderConfig::from_json(c.to_json(), "test");
  CHECK(back.to_json() == c.to_json());

  CHECK_THROWS_AS(render::RenderConfig::from_json(Json{{"samples", 3}}, "test"), ConfigError);
  CHECK_THROWS_AS(render::RenderConfig::from_json(Json{{"weights", {{"dpth", 1.0}}}}, "test"),
                  ConfigError);
  CHECK_THROWS_AS(render::RenderConfig::from_json(Json{{"far_m", 0.5}}, "test"), ConfigError);
  CHECK_THROWS_AS(render::RenderConfig::from_json(Json{{"n_samples", 0}}, "test"), ConfigError);
  CHECK_THROWS_AS(
      render::RenderConfig::from_json(Json{{"patch_rows", 1}, {"patch_cols", 1}}, "test"),
      ConfigError);
  CHECK(k.patch_rows == 2);
  CHECK(k.patch_cols == 8);
  CHECK(k.grad_l1);
  CHECK(render::RenderConfig::from_json(Json::object(), "test").to_json() ==
        render::RenderConfig().to_json());
  // eval_depth: "expected" (default, absent from the JSON) or "median"; anything else rejected.
  CHECK_FALSE(k.to_json().contains("eval_depth"));
  auto m = k;
  m.eval_depth = "median";
  CHECK(render::RenderConfig::from_json(m.to_json(), "test").eval_depth == "median");
  CHECK(m.to_json().at("eval_depth") == "median");
  CHECK_THROWS_WITH(render::RenderConfig::from_json(Json{{"eval_depth", "mean"}}, "test"),
                    Catch::Contains("eval_depth") && Catch::Contains("mean"));
  CHECK(k.bin_width(0.5f) == Approx(80.0 * 0.5 / 64));
}
