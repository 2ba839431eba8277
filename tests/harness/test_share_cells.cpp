// `sgnlf merge --share-cells` (harness/combine.hpp, results/schema.md "Combined tables"): a row
// two tables share, on sequences both define alike, is run once. Another table's results give
// this table's rows their runs there; their other rows and sequences are left out and listed;
// their sources name the table and the file they came through; the run files a combined input
// of the other table kept are copied. Fake hooks, no training.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "core/config.hpp"
#include "fake_table.hpp"
#include "harness/combine.hpp"
#include "harness/results.hpp"
#include "harness/run_files.hpp"

using namespace sgnlf;
namespace fs = std::filesystem;

namespace {

using Inputs = std::vector<std::pair<std::string, Json>>;

// The fake smoke `table` at `seed` (only sg-nlf and lidar-nerf run in the fake).
Json run(const std::string& table, uint64_t seed) {
  auto o = test::fake_options({seed});
  o.table = table;
  return Json::parse(harness::run_table(o, test::fake_hooks(), test::fake_context()).dump());
}

harness::BenchHooks hooks() {
  auto h = test::fake_hooks();
  h.config_hash = [](const std::string&, const std::string&) { return std::string(); };
  return h;
}

Json combine(const Inputs& in, bool share, const std::string& out = "/o") {
  return harness::combine_tables(in, harness::CombineOptions{false, share}, hooks(), "sgnlf merge", out);
}

const Json& entry_of(const Json& r, const std::string& method, const std::string& seq) {
  for (const auto& row : r.at("rows"))
    if (row.at("method") == method)
      for (const auto& e : row.at("sequences"))
        if (e.at("sequence") == seq) return e;
  throw std::out_of_range("no entry " + method + " / " + seq);
}

}  // namespace

TEST_CASE("merge takes another table's runs of a shared row only with --share-cells",
          "[harness][merge]") {
  // The ablation's smoke scale has nuscenes-low-a; nuscenes-low's has a and b, defined alike.
  const Inputs in{{"abl/results.json", run("ablation-nuscenes", 1)},
                  {"nus/results.json", run("nuscenes-low", 2)}};
  CHECK_THROWS_WITH(combine(in, false), Catch::Contains("different table") &&
                                            Catch::Contains("--share-cells"));
  const Json r = combine(in, true);
  CHECK(r["table"] == "ablation-nuscenes");
  // SG-NLF (full) on nuscenes-low-a: seed 1 from the ablation, seed 2 from nuscenes-low.
  const Json& e = entry_of(r, "sg-nlf", "nuscenes-low-a");
  REQUIRE(e.contains("runs"));
  REQUIRE(e["runs"].size() == 2);
  CHECK(e["runs"][1]["seed"] == 2);
  const Json& files = r["combined_from"]["files"];
  const Json& src = files.at(e["runs"][1]["source"].get<size_t>());
  CHECK(src["table"] == "nuscenes-low");
  CHECK(src["via"] == "nus/results.json");
  CHECK_FALSE(files.at(e["runs"][0]["source"].get<size_t>()).contains("table"));
  // nuscenes-low-b is not a sequence of the ablation: left out, never a sequence of the output.
  const Json& sh = r["combined_from"]["shared"];
  REQUIRE(sh.size() == 1);
  CHECK(sh[0]["table"] == "nuscenes-low");
  CHECK(sh[0]["taken"] == Json::array({Json{{"method", "sg-nlf"}, {"sequence", "nuscenes-low-a"}}}));
  bool b_left_out = false;
  for (const auto& x : sh[0]["left_out"])
    b_left_out |= x.value("sequence", "") == "nuscenes-low-b" &&
                  x.value("why", "") == "not a sequence of ablation-nuscenes at scale smoke";
  CHECK(b_left_out);
  for (const auto& s : r["sequences"]) CHECK(s["name"] == "nuscenes-low-a");
  // The other table's timings are its own.
  CHECK(r["timings"]["total_s"] == in[0].second["timings"]["total_s"]);
}

TEST_CASE("a shared merge refuses another scale and takes only this table's rows",
          "[harness][merge]") {
  auto o = test::fake_options({1});
  o.table = "nuscenes-low";
  o.scale = "quick";
  o.sequences = {"nuscenes-low-a"};
  const Json quick = Json::parse(harness::run_table(o, test::fake_hooks(), test::fake_context()).dump());
  CHECK_THROWS_WITH(combine({{"abl", run("ablation-nuscenes", 1)}, {"nus", quick}}, true),
                    Catch::Contains("different scale"));
  // kitti360-standard's lidar-nerf is no row of kitti360-low: left out, nothing taken.
  const Json r = combine({{"low", run("kitti360-low", 1)}, {"std", run("kitti360-standard", 1)}}, true);
  const Json& sh = r["combined_from"]["shared"][0];
  CHECK(sh["taken"].empty());
  bool lidar_nerf = false;
  for (const auto& x : sh["left_out"])
    lidar_nerf |= x.value("method", "") == "lidar-nerf" &&
                  x.value("why", "") == "not a row of kitti360-low";
  CHECK(lidar_nerf);
}

TEST_CASE("a shared merge copies the run files the other table kept", "[harness][merge]") {
  const fs::path root = fs::temp_directory_path() / "sgnlf-share-cells";
  fs::remove_all(root);
  // nuscenes-low as committed: a combined table with its run files under runs/.
  const fs::path nus = root / "nuscenes-low" / "smoke";
  fs::create_directories(nus);
  const Json nus_table = combine({{"cell/results.json", run("nuscenes-low", 2)}}, false, nus.string());
  write_json_file((nus / "results.json").string(), nus_table);
  const fs::path kept = nus / "runs/sg-nlf/nuscenes-low-a/seed2";
  fs::create_directories(kept);
  for (const char* f : {"metrics.json", "summary.json"}) std::ofstream(kept / f) << "nus " << f;
  const fs::path out = root / "ablation-nuscenes" / "smoke";
  // The ablation as committed (a combined table: its own runs are carried, not copied again).
  const Json abl_table = combine({{"abl-cell/results.json", run("ablation-nuscenes", 1)}}, false, out.string());
  const Inputs in{{(out / "results.json").string(), abl_table},
                  {(nus / "results.json").string(), nus_table}};
  const Json r = combine(in, true, out.string());
  const auto k = harness::keep_run_files(r, in, out.string());
  REQUIRE(k.copied.size() == 2);  // the shared run's metrics.json and summary.json
  std::string text;
  std::getline(std::ifstream(out / "runs/sg-nlf/nuscenes-low-a/seed2/metrics.json"), text);
  CHECK(text == "nus metrics.json");
  fs::remove_all(root);
}
