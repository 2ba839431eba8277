// Tables run as cells (--cells / --cell K / merge): the cell list, a merge equal to the
// one-process run (one seed and several, with a failing row), and the merge's refusals.
// Fake hooks, no training.
#include <catch2/catch.hpp>

#include "core/config.hpp"
#include "fake_table.hpp"
#include "harness/cells.hpp"
#include "harness/markdown.hpp"
#include "harness/results.hpp"

using namespace sgnlf;

namespace {

// Every cell run on its own (a fresh cache each, as in separate processes), written and read
// back as JSON text, as `sgnlf merge` reads the files.
std::vector<std::pair<std::string, Json>> run_cells(const harness::BenchOptions& o,
                                                    const harness::BenchHooks& h) {
  const auto plan = harness::plan_table(o, h);
  std::vector<std::pair<std::string, Json>> cells;
  for (const auto& c : plan.cells)
    cells.emplace_back("cell" + std::to_string(c.index) + ".json",
                       Json::parse(harness::run_cell(o, h, long(c.index), test::fake_context()).dump()));
  return cells;
}

}  // namespace

TEST_CASE("--cells lists row × sequence × seed, running rows only", "[harness][cells]") {
  const auto h = test::fake_hooks();
  auto plan = harness::plan_table(test::fake_options(), h);
  const auto lines = harness::cell_lines(plan);
  REQUIRE(lines.size() == 4);  // lidar-nerf and sg-nlf run (fake hooks) × 2 sequences
  CHECK(lines[0] == "0\tlidar-nerf\tkitti360-1538\t7");
  CHECK(lines[3] == "3\tsg-nlf\tkitti360-1728\t7");
  plan = harness::plan_table(test::fake_options({1, 2, 3}), h);
  REQUIRE(plan.cells.size() == 12);
  CHECK(harness::cell_lines(plan)[4] == "4\tlidar-nerf\tkitti360-1728\t2");
  auto sub = test::fake_options();
  sub.rows = {"sg-nlf"};
  CHECK(harness::plan_table(sub, h).cells.size() == 2);
  CHECK_THROWS_AS(harness::run_cell(test::fake_options(), h, 4, test::fake_context()), ConfigError);
  CHECK_THROWS_AS(harness::run_cell(test::fake_options(), h, -1, test::fake_context()), ConfigError);
}

TEST_CASE("merge: cells run apart equal the one-process table", "[harness][cells]") {
  struct Case {
    std::vector<uint64_t> seeds;
    bool fail;
  };
  for (const Case& k : {Case{{}, false}, Case{{1, 2, 3}, false}, Case{{}, true},
                        Case{{2, 5}, true}}) {
    CAPTURE(k.seeds, k.fail);
    const auto o = test::fake_options(k.seeds);
    const auto h = test::fake_hooks(nullptr, k.fail, true);
    const Json one = harness::run_table(o, h, test::fake_context());
    const Json merged = harness::merge_cells(run_cells(o, h), "sgnlf merge", "/elsewhere");
    CHECK(harness::table_differences(merged, one).empty());
    CHECK(merged["out_dir"] == "/elsewhere");
    CHECK(merged["merged_from"]["cells"] == harness::plan_table(o, h).cells.size());
    CHECK(harness::render_markdown(merged).find("| LiDAR-NeRF |") != std::string::npos);
    // The comparison can fail: one cell's metric changed.
    auto cells = run_cells(o, h);
    cells[1].second["outcome"]["entry"]["metrics"]["cd"] = 9.0;
    const auto diff =
        harness::table_differences(harness::merge_cells(cells, "m", "/x"), one);
    CHECK_FALSE(diff.empty());
  }
  // A failed row keeps the runs before the failure, as in one process.
  const auto h = test::fake_hooks(nullptr, true);
  const Json merged = harness::merge_cells(run_cells(test::fake_options(), h), "m", "/x");
  CHECK(merged["rows"][4]["status"] == "failed");
  CHECK(merged["rows"][4]["error"].get<std::string>().find("kitti360-1538: fake divergence") == 0);
}

TEST_CASE("merge refuses missing, repeated and foreign cells, naming the files",
          "[harness][cells]") {
  const auto h = test::fake_hooks();
  const auto cells = run_cells(test::fake_options(), h);
  auto missing = cells;
  missing.erase(missing.begin() + 2);
  CHECK_THROWS_WITH(harness::merge_cells(missing, "m", "/x"),
                    Catch::Contains("1 of 4 cells missing: 2 (sg-nlf / kitti360-1538 / seed 7)"));
  auto twice = cells;
  twice.push_back({"again.json", cells[1].second});
  CHECK_THROWS_WITH(harness::merge_cells(twice, "m", "/x"),
                    Catch::Contains("given twice: cell1.json and again.json"));
  // Another seed (config), another commit, another device, another table's cell.
  auto other = cells;
  other[3].second = run_cells(test::fake_options({8}), h)[3].second;
  CHECK_THROWS_WITH(harness::merge_cells(other, "m", "/x"),
                    Catch::Contains("cell0.json and cell3.json are from different config"));
  other = cells;
  other[2].second["context"]["git"]["sha"] = "ffffffffffffffffffffffffffffffffffffffff";
  CHECK_THROWS_WITH(harness::merge_cells(other, "m", "/x"),
                    Catch::Contains("cell0.json and cell2.json are from different commit"));
  other = cells;
  other[1].second["context"]["opencl"]["device"] = "another device";
  CHECK_THROWS_WITH(harness::merge_cells(other, "m", "/x"), Catch::Contains("OpenCL device"));
  auto low = test::fake_options();
  low.table = "kitti360-low";
  other = cells;
  other[1].second = run_cells(low, h).at(0).second;
  CHECK_THROWS_WITH(harness::merge_cells(other, "m", "/x"),
                    Catch::Contains("cell0.json and cell1.json are from different table"));
  // Not a cell file (a results.json), a cell whose identity does not match its index, a bad
  // outcome.
  other = cells;
  other[0] = {"results.json", test::fake_results()};
  CHECK_THROWS_WITH(harness::merge_cells(other, "m", "/x"),
                    Catch::Contains("results.json is not a sgnlf.cell v1 cell file"));
  other = cells;
  other[2].second["cell"]["method"] = "lidar-nerf";
  CHECK_THROWS_WITH(harness::merge_cells(other, "m", "/x"),
                    Catch::Contains("cell2.json: cell"));
  other = cells;
  other[2].second["outcome"]["status"] = "great";
  CHECK_THROWS_WITH(harness::merge_cells(other, "m", "/x"),
                    Catch::Contains("cell2.json: outcome.status 'great'"));
  CHECK_THROWS_AS(harness::merge_cells({}, "m", "/x"), ConfigError);
}

TEST_CASE("every run of a table or a cell is told the bench's context (its summary.json keeps it)",
          "[harness][cells]") {
  auto h = test::fake_hooks();
  std::vector<Json> seen;
  const auto run = h.run;
  h.run = [&seen, run](const pipeline::MethodRequest& r) {
    seen.push_back(r.context);
    return run(r);
  };
  harness::run_table(test::fake_options(), h, test::fake_context());
  REQUIRE(seen.size() == 4);
  for (const auto& c : seen) CHECK(c == test::fake_context());
  seen.clear();
  harness::run_cell(test::fake_options(), h, 2, test::fake_context());
  REQUIRE(seen.size() == 1);
  CHECK(seen[0] == test::fake_context());
}
