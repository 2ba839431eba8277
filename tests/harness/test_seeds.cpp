// Several seeds (--seeds): mean ± sample sd per row and sequence, each seed's runs kept, and
// the seed-spread rule of compare. Fake hooks, no training.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/config.hpp"
#include "fake_table.hpp"
#include "harness/runner.hpp"
#include "harness/compare.hpp"
#include "harness/markdown.hpp"
#include "harness/results.hpp"

using namespace sgnlf;

TEST_CASE("--seeds: mean ± sample sd per row and sequence, every seed's runs kept",
          "[harness][seeds]") {
  const auto o = test::fake_options({1, 2, 3});
  const Json r = harness::run_table(o, test::fake_hooks(nullptr, false, true), test::fake_context());
  CHECK(r["config"]["seeds"] == Json::array({1, 2, 3}));
  CHECK_FALSE(r["config"].contains("seed"));
  CHECK(r["seeds"]["table_seeds"] == Json::array({1, 2, 3}));
  CHECK(r["seeds"]["runs"].size() == 2 * 2 * 3);  // 2 running rows × 2 sequences × 3 seeds
  const Json& nerf = r["rows"][0];
  REQUIRE(nerf["status"] == "ok");
  // Per seed s the mean cd over the 2 sequences is 0.11 + 0.01 (s − 1): mean 0.12, sd 0.01.
  CHECK(nerf["mean"]["cd"].get<double>() == Approx(0.12));
  CHECK(nerf["mean_sd"]["cd"].get<double>() == Approx(0.01));
  CHECK(nerf["mean_sd"]["fscore"].get<double>() == Approx(0.0).margin(1e-12));
  CHECK(nerf["mean_sd"]["depth_lpips"].is_null());
  REQUIRE(nerf["mean_by_seed"].size() == 3);
  CHECK(nerf["mean_by_seed"][2]["seed"] == 3);
  CHECK(nerf["mean_by_seed"][2]["mean"]["cd"].get<double>() == Approx(0.13));
  CHECK(nerf["diff_vs_paper"]["cd"]["ours"].get<double>() == Approx(0.12));
  // One entry per sequence: the mean and spread over seeds, and each seed's run.
  REQUIRE(nerf["sequences"].size() == 2);
  const Json& s1 = nerf["sequences"][1];
  CHECK(s1["sequence"] == "kitti360-1728");
  CHECK(s1["seeds"] == Json::array({1, 2, 3}));
  CHECK(s1["metrics"]["cd"].get<double>() == Approx(0.13));
  CHECK(s1["metrics_sd"]["cd"].get<double>() == Approx(0.01));
  REQUIRE(s1["runs"].size() == 3);
  CHECK(s1["runs"][1]["seed"] == 2);
  CHECK(s1["runs"][1]["metrics"]["cd"].get<double>() == Approx(0.13));
  CHECK(s1["runs"][1]["run_dir"] == "/nonexistent/out/runs/lidar-nerf/kitti360-1728/seed-2");
  CHECK(r["rows"][4]["sequences"][0]["pose_metrics"]["ate_m"].get<double>() == Approx(0.07));
  CHECK(nerf["timings"]["step"]["n"] == 6 * 6);
  // table.md: mean ± sd cells and the seeds in the header.
  const std::string md = harness::render_markdown(r);
  CHECK(md.find("seeds 1, 2, 3") != std::string::npos);
  CHECK(md.find("| LiDAR-NeRF | 0.1200 ± 0.0100 | 0.0923 | +0.0277 |") != std::string::npos);
  CHECK(md.find("0.1300 ± 0.0100") != std::string::npos);  // per-sequence table
}

TEST_CASE("--seeds with one seed is the single-seed result; a repeated seed is an error",
          "[harness][seeds]") {
  const Json single = test::fake_results();
  const Json one = harness::run_table(test::fake_options({7}), test::fake_hooks(), test::fake_context());
  CHECK(one["config"] == single["config"]);
  CHECK(one["config_hash"] == single["config_hash"]);
  CHECK_FALSE(one["seeds"].contains("table_seeds"));
  CHECK_FALSE(one["rows"][0].contains("mean_sd"));
  CHECK(one["seeds"] == single["seeds"]);
  for (size_t i = 0; i < single["rows"].size(); ++i) {
    CHECK(one["rows"][i]["mean"] == single["rows"][i]["mean"]);
    CHECK(one["rows"][i]["sequences"].size() == single["rows"][i]["sequences"].size());
  }
  CHECK(one["rows"][0]["sequences"][0]["run_dir"] == "/nonexistent/out/runs/lidar-nerf/kitti360-1538");
  CHECK_THROWS_WITH(test::fake_options({1, 2, 1}).validate(), Catch::Contains("seed 1 is listed twice"));
}

TEST_CASE("compare with several seeds: loose allows twice the standard error of the difference",
          "[harness][seeds][compare]") {
  const Json base =
      harness::run_table(test::fake_options({1, 2, 3}), test::fake_hooks(nullptr, false, true), test::fake_context());
  CHECK_FALSE(harness::compare_results(base, base).regression());
  // Loose cd allowance at 0.12: 0.005 + 1.4 × 0.12 = 0.173; 2 SE = 2 √(0.01²/3 + 0.01²/3) = 0.0163.
  const double tol = harness::metric_tolerance("cd", "loose", 0.12);
  const double two_se = 2 * std::sqrt(2 * 0.01 * 0.01 / 3);
  Json within = base;
  test::row(within, "lidar-nerf")["mean"]["cd"] = 0.12 + tol + 0.5 * two_se;
  auto rep = harness::compare_results(within, base, {"loose"});
  CHECK_FALSE(rep.regression());
  CHECK(rep.seed_spread_used > 0);
  // One side a single run (no spread of its own): it is one more draw of the other side's
  // spread, allowance 2 sd √(1 + 1/n) = 2 × 0.01 × √(4/3); beyond it fails.
  const double one_draw = 2 * 0.01 * std::sqrt(4.0 / 3.0);
  Json one_side = within;
  test::row(one_side, "lidar-nerf").erase("mean_by_seed");
  test::row(one_side, "lidar-nerf")["mean"]["cd"] = 0.12 + tol + 0.9 * one_draw;
  CHECK_FALSE(harness::compare_results(one_side, base, {"loose"}).regression());
  test::row(one_side, "lidar-nerf")["mean"]["cd"] = 0.12 + tol + 1.1 * one_draw;
  CHECK(harness::compare_results(one_side, base, {"loose"}).regression());
  // Beyond the tolerance plus 2 SE fails.
  Json beyond = base;
  test::row(beyond, "lidar-nerf")["mean"]["cd"] = 0.12 + tol + 1.2 * two_se;
  CHECK(harness::compare_results(beyond, base, {"loose"}).regression());
  // Tight (same device and configs): no spread allowance, and every seed's run is compared.
  rep = harness::compare_results(within, base);
  CHECK(rep.mode == "tight");
  CHECK(rep.regression());
  Json one_seed = base;
  test::row(one_seed, "lidar-nerf")["sequences"][0]["runs"][1]["metrics"]["cd"] = 0.5;
  rep = harness::compare_results(one_seed, base);
  REQUIRE(rep.regression());
  bool named = false;
  for (const auto& f : rep.findings) named |= f.fails && f.where.find("seed 2") != std::string::npos;
  CHECK(named);
}
