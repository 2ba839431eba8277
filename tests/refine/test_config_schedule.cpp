// Host-only parts of the ray-drop refinement: the config (defaults, strict reader, refused
// values naming the key), the box draws (deterministic per seed, inside the image, LiDAR4D's
// size limits) and the one-cycle learning rate.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/config.hpp"
#include "core/error.hpp"
#include "refine/box_dropout.hpp"
#include "refine/one_cycle.hpp"
#include "refine/ray_drop_unet_config.hpp"

using namespace sgnlf;

TEST_CASE("Ray-drop U-Net config: defaults, strict reader, refused values", "[refine][config]") {
  const refine::RayDropUNetConfig d;
  REQUIRE_NOTHROW(d.validate());
  CHECK(d.channels == 32);
  CHECK(d.depth == 4);
  CHECK(d.steps == 1000);
  const auto j = d.to_json();
  CHECK(j.at("schedule") == "one_cycle");
  const auto back = refine::RayDropUNetConfig::from_json(j);
  CHECK(back.to_json() == j);
  const auto c = refine::RayDropUNetConfig::from_json(
      Json::parse(R"({"channels": 16, "depth": 2, "schedule": "constant", "steps": 10})"));
  CHECK(c.channels == 16);
  CHECK(c.schedule == refine::LrSchedule::constant);
  auto refuse = [](const char* text, const char* what) {
    REQUIRE_THROWS_WITH(refine::RayDropUNetConfig::from_json(Json::parse(text)),
                        Catch::Contains(what));
  };
  refuse(R"({"chanels": 32})", "chanels");                   // unknown key, named
  refuse(R"({"channels": 24})", "'channels' = 24");          // not a multiple of 16
  refuse(R"({"depth": 0})", "'depth'");
  refuse(R"({"channels": 256, "depth": 3})", "2048-channel");  // widest concatenation
  refuse(R"({"schedule": "step"})", "one_cycle");            // the names are listed
  refuse(R"({"box_frac": 1.5})", "'box_frac'");
  refuse(R"({"pct_start": 1.0})", "'pct_start'");
  refuse(R"({"steps": 2.5})", "steps");
}

TEST_CASE("Box draws are deterministic per seed and respect LiDAR4D's limits",
          "[refine][boxes]") {
  const int h = 66, w = 1030, steps = 200;
  const auto a = refine::draw_boxes(7, steps, h, w, 32, 0.1f);
  const auto b = refine::draw_boxes(7, steps, h, w, 32, 0.1f);
  const auto c = refine::draw_boxes(8, steps, h, w, 32, 0.1f);
  CHECK(a.boxes == b.boxes);
  CHECK(a.count == b.count);
  CHECK(a.boxes != c.boxes);
  REQUIRE(a.first.size() == size_t(steps));
  int max_count = 0, total = 0, max_h = 0, max_w = 0;
  for (int s = 0; s < steps; ++s) {
    CHECK(a.first[size_t(s)] == total);
    total += a.count[size_t(s)];
    max_count = std::max(max_count, a.count[size_t(s)]);
  }
  REQUIRE(a.boxes.size() == size_t(total) * 4);
  for (size_t i = 0; i < a.boxes.size(); i += 4) {
    const int y0 = a.boxes[i], x0 = a.boxes[i + 1], y1 = a.boxes[i + 2], x1 = a.boxes[i + 3];
    REQUIRE(y0 >= 0);
    REQUIRE(x0 >= 0);
    REQUIRE(y1 <= h - 1);  // LiDAR4D: corner in [0, h − height), so the last row stays
    REQUIRE(x1 <= w - 1);
    REQUIRE(y1 - y0 >= 1);
    REQUIRE(x1 - x0 >= 1);
    max_h = std::max(max_h, y1 - y0);
    max_w = std::max(max_w, x1 - x0);
  }
  CHECK(max_count == 31);  // k ∈ [0, 32): 200 steps reach the top
  CHECK(total > 200 * 12);  // mean 15.5
  CHECK(max_h == 5);       // heights in [1, ⌊0.1 · 66⌋ = 6)
  CHECK(max_w == 102);     // widths in [1, 103)
  CHECK(refine::draw_boxes(7, 5, h, w, 0, 0.1f).boxes.empty());
  // A tiny image still gets boxes of at least one pixel.
  CHECK_NOTHROW(refine::draw_boxes(7, 5, 4, 4, 32, 0.1f));
  REQUIRE_THROWS_WITH(refine::draw_boxes(7, 5, 1, 4, 32, 0.1f), Catch::Contains("1 x 4"));
}

TEST_CASE("One-cycle learning rate follows PyTorch's OneCycleLR (cosine)", "[refine][lr]") {
  refine::RayDropUNetConfig c;  // 1000 steps, lr 1e-3, pct_start 0.3, 25, 1e4
  CHECK(refine::learning_rate(c, 0) == Approx(1e-3 / 25).epsilon(1e-6));
  CHECK(refine::learning_rate(c, 299) == Approx(1e-3).epsilon(1e-6));  // 0.3 · 1000 − 1
  CHECK(refine::learning_rate(c, 999) == Approx(1e-3 / 25 / 1e4).epsilon(1e-5));
  // Halfway up: the mean of start and peak (cos(π/2) = 0).
  CHECK(refine::learning_rate(c, 149) == Approx(0.5 * (1e-3 / 25 + 1e-3)).epsilon(1e-2));
  for (int s = 1; s < 1000; ++s) {
    if (s <= 299) REQUIRE(refine::learning_rate(c, s) > refine::learning_rate(c, s - 1));
    else REQUIRE(refine::learning_rate(c, s) < refine::learning_rate(c, s - 1));
  }
  c.schedule = refine::LrSchedule::constant;
  CHECK(refine::learning_rate(c, 500) == c.lr);
}
