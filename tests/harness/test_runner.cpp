// Table definitions, the table runner (with fake hooks) and the markdown renderer: means over
// sequences, differences to the paper, "not implemented" and "failed" rows kept in place.
#include <catch2/catch.hpp>

#include "fake_table.hpp"
#include "harness/markdown.hpp"
#include "harness/results.hpp"
#include "harness/schema.hpp"
#include "harness/tables.hpp"

using namespace sgnlf;

TEST_CASE("every table parses and its columns and paper numbers are consistent", "[harness]") {
  const auto names = harness::table_names();
  REQUIRE(names.size() == 4);
  for (const auto& n : names) {
    const auto t = harness::table_def(n);
    CHECK_FALSE(t.rows.empty());
    for (const auto& c : t.columns) CHECK(harness::metric_info(c) != nullptr);
    for (const auto& c : t.extra_columns) CHECK(harness::metric_info(c) != nullptr);
    for (const auto& s : harness::scale_names()) {
      const auto seqs = harness::table_sequences(t, s, false);
      CHECK_FALSE(seqs.empty());
      if (s == "smoke")
        for (const auto& q : seqs) CHECK((q.frames > 0 && q.frames <= 16 && q.width <= 256));
    }
    CHECK_FALSE(harness::table_sequences(t, "quick", true).empty());
    // Every paper number is for a row of the table and a known metric.
    for (const auto& r : t.rows) {
      const Json p = harness::paper_numbers(n, r.method);
      for (auto it = p.begin(); it != p.end(); ++it) CHECK(harness::metric_info(it.key()) != nullptr);
    }
  }
  // Spot checks against protocol §5.
  CHECK(harness::paper_numbers("kitti360-standard", "lidar-nerf")["cd"] == 0.0923);
  CHECK(harness::paper_numbers("kitti360-low", "sg-nlf")["depth_rmse"] == 2.9514);
  CHECK(harness::paper_numbers("nuscenes-low", "geonlf")["intensity_rmse"] == 0.0378);
  CHECK(harness::paper_numbers("ablation-nuscenes", "sg-nlf-no-graph")["ate_m"] == 0.798);
  CHECK(harness::unverified_numbers("nuscenes-low", "sg-nlf")["ate_m"] == 0.071);
  CHECK(harness::paper_numbers("kitti360-standard", "nonexistent").empty());
  CHECK_THROWS_AS(harness::table_def("kitti-999"), ConfigError);
  CHECK_THROWS_AS(harness::table_sequences(harness::table_def("kitti360-low"), "huge", false),
                  ConfigError);
}

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

TEST_CASE("markdown: ours beside the paper, not implemented rows, per-sequence tables",
          "[harness]") {
  const Json r = test::fake_results(true);
  const std::string md = harness::render_markdown(r);
  CHECK(md.find("| LiDAR-NeRF | 0.1100 | 0.0923 | +0.0177 |") != std::string::npos);
  CHECK(md.find("| LiDAR4D | not implemented | 0.0894 | — |") != std::string::npos);
  CHECK(md.find("| SG-NLF | failed | 0.0867 | — |") != std::string::npos);
  CHECK(md.find("## Sequence kitti360-1538") != std::string::npos);
  CHECK(md.find("## Sequence kitti360-1728") != std::string::npos);
  CHECK(md.find("fake divergence") != std::string::npos);
  // The naive baseline reported by the runs: mean over sequences (0.2 + 0.3) / 2.
  CHECK(md.find("| *naive baseline (nearest training scan)* | 0.2500 | | | 18.00 | | | — | | |") !=
        std::string::npos);
  CHECK(harness::format_metric("depth_psnr", Json(20.456)) == "20.46");
  CHECK(harness::format_metric("cd", Json()) == "—");
}
