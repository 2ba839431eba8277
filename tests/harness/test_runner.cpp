// The table runner with fake hooks (fake_table.hpp): rows in table order, means over
// sequences, differences to the paper, seeds and timings; --rows / --sequences subsets;
// "not implemented" and "failed" rows kept in place.
#include <catch2/catch.hpp>

#include "core/config.hpp"
#include "fake_table.hpp"
#include "harness/markdown.hpp"
#include "harness/schema.hpp"

using namespace sgnlf;

TEST_CASE("run_table: rows, means, paper differences, seeds", "[harness]") {
  int prepares = 0;
  const Json r = test::fake_results(false, &prepares);
  CHECK(prepares == 2);  // each sequence prepared once, shared by the rows
  CHECK(r["schema"] == harness::kSchemaName);
  CHECK(r["schema_version"] == harness::kSchemaVersion);
  CHECK(r["table"] == "kitti360-standard");
  CHECK(r["config"]["seed"] == 7);
  CHECK(r["config_hash"].get<std::string>().size() == 16);
  REQUIRE(r["rows"].size() == 5);  // not-implemented rows are kept, in table order
  CHECK(r["rows"][0]["method"] == "lidar-nerf");
  CHECK(r["rows"][1]["status"] == "not_implemented");
  CHECK(r["rows"][2]["status"] == "not_implemented");
  CHECK(r["rows"][3]["method"] == "geonlf-frozen");
  const Json& nerf = r["rows"][0];
  REQUIRE(nerf["status"] == "ok");
  // Mean over the 2 sequences: cd (0.10 + 0.12) / 2, depth PSNR (20 + 21) / 2.
  CHECK(nerf["mean"]["cd"].get<double>() == Approx(0.11));
  CHECK(nerf["mean"]["depth_psnr"].get<double>() == Approx(20.5));
  CHECK(nerf["mean"]["depth_lpips"].is_null());
  CHECK(nerf["diff_vs_paper"]["cd"]["diff"].get<double>() == Approx(0.11 - 0.0923));
  CHECK(nerf["diff_vs_paper"]["cd"]["better"] == false);
  CHECK(nerf["diff_vs_paper"]["depth_psnr"]["paper"] == 26.77);
  const Json& sg = r["rows"][4];
  CHECK(sg["mean"]["ate_m"].get<double>() == Approx(0.07));
  CHECK(sg["diff_vs_paper"]["cd"]["better"] == true);           // 0.055 < 0.0867
  CHECK(sg["diff_vs_paper"]["depth_psnr"]["better"] == false);  // 22.5 < 32.72
  // Timings: repetitions gathered over sequences, with median/min/max.
  CHECK(nerf["timings"]["step"]["n"] == 12);
  CHECK(nerf["timings"]["train"]["median"].get<double>() == Approx(1.5));
  CHECK(nerf["timings"]["train"]["max"].get<double>() == Approx(2.0));
  // Seeds of every run.
  CHECK(r["seeds"]["table_seed"] == 7);
  CHECK(r["seeds"]["runs"].size() == 4);
  CHECK(nerf["sequences"][0]["per_frame"].size() == 1);
  CHECK(nerf["sequences"][1]["dataset"]["name"] == "kitti360-1728");
}

TEST_CASE("run_table: --rows and --sequences run a subset, the others are marked skipped",
          "[harness]") {
  harness::BenchOptions o;
  o.table = "kitti360-standard";
  o.scale = "smoke";
  o.out_dir = "/nonexistent/out";
  o.rows = {"sg-nlf"};
  o.sequences = {"kitti360-1728"};
  int prepares = 0;
  const Json r = harness::run_table(o, test::fake_hooks(&prepares), test::fake_context());
  CHECK(prepares == 1);
  REQUIRE(r["rows"].size() == 5);  // every row kept, in table order
  CHECK(r["rows"][0]["status"] == "skipped");  // lidar-nerf would run but was not chosen
  CHECK(r["rows"][4]["status"] == "ok");
  REQUIRE(r["rows"][4]["sequences"].size() == 1);
  CHECK(r["rows"][4]["mean"]["cd"].get<double>() == Approx(0.5 * 0.12));
  CHECK(r["config"]["rows"] == Json::array({"sg-nlf"}));
  CHECK(r["config_hash"] != test::fake_results()["config_hash"]);
  CHECK(harness::render_markdown(r).find("not run (--rows)") != std::string::npos);
  // A full table's config has no subset keys (its hash is unchanged by the feature).
  CHECK_FALSE(test::fake_results()["config"].contains("rows"));
  o.rows = {"lidar-nerf", "nope"};
  CHECK_THROWS_WITH(o.validate(), Catch::Contains("no row 'nope'"));
  o.rows = {};
  o.sequences = {"kitti360-3353"};  // a quick/paper sequence, not in smoke
  CHECK_THROWS_WITH(o.validate(), Catch::Contains("no sequence 'kitti360-3353'"));
}

TEST_CASE("a failing row is recorded with its error and the table goes on", "[harness]") {
  const Json r = test::fake_results(true);
  CHECK(r["rows"][0]["status"] == "ok");
  CHECK(r["rows"][4]["status"] == "failed");
  CHECK(r["rows"][4]["error"].get<std::string>().find("fake divergence") != std::string::npos);
}
