// The time estimate `sgnlf bench` prints before a run: each cell takes what the same row x
// sequence took in a previous run, else that row's median; other tables or scales are refused.
#include <catch2/catch.hpp>

#include "core/config.hpp"
#include "fake_table.hpp"
#include "harness/estimate.hpp"

using namespace sgnlf;

namespace {
// Sets every sequence's harness_wall_s of `method` in a results JSON to `per_seq[k]`.
void set_walls(Json& r, const std::string& method, const std::vector<double>& per_seq,
               double row_median) {
  Json& row = test::row(r, method);
  for (size_t k = 0; k < row["sequences"].size(); ++k)
    row["sequences"][k]["timings"]["harness_wall_s"] = per_seq.at(k);
  row["timings"]["harness_wall_s"] = Json{{"reps", per_seq}, {"n", per_seq.size()},
                                          {"median", row_median}};
}
}  // namespace

TEST_CASE("a table's time is estimated from a previous run, cell by cell", "[harness][estimate]") {
  Json prev = test::fake_results();
  set_walls(prev, "lidar-nerf", {100, 300}, 200);
  set_walls(prev, "sg-nlf", {1000, 3000}, 2000);
  prev["timings"]["prepare_s"] = Json{{"reps", {2.0, 4.0}}, {"median", 3.0}};

  const auto plan = harness::plan_table(test::fake_options(), test::fake_hooks());
  REQUIRE(plan.cells.size() == 4);  // 2 rows that run x 2 sequences
  const auto est = harness::estimate_table(plan, "smoke", prev, "prev.json");
  CHECK(est.unknown == 0);
  CHECK(est.prepare_s == Approx(2 * 3.0));
  CHECK(est.total_s == Approx(100 + 300 + 1000 + 3000 + 6));
  for (const auto& c : est.cells) CHECK(c.basis == "cell");
  CHECK(est.device == "fake-device");
  CHECK(est.summary().find("1 h 13 min") != std::string::npos);

  SECTION("a sequence never run takes the row's median; a row never run is unknown") {
    Json part = prev;
    test::row(part, "lidar-nerf")["sequences"].erase(1);
    part["rows"].erase(part["rows"].begin() + 0);  // drop the first row (lidar-nerf)
    const auto e2 = harness::estimate_table(plan, "smoke", part, "part.json");
    CHECK(e2.unknown == 2);  // lidar-nerf on both sequences
    CHECK(e2.total_s == Approx(1000 + 3000 + 6));
    Json half = prev;
    test::row(half, "sg-nlf")["sequences"].erase(1);
    const auto e3 = harness::estimate_table(plan, "smoke", half, "half.json");
    CHECK(e3.unknown == 0);
    CHECK(e3.total_s == Approx(100 + 300 + 1000 + 2000 + 6));
    bool median_used = false;
    for (const auto& c : e3.cells) median_used |= c.basis == "row median";
    CHECK(median_used);
  }
  SECTION("a run of several seeds counts every seed's cell") {
    const auto plan3 = harness::plan_table(test::fake_options({1, 2, 3}), test::fake_hooks());
    const auto e = harness::estimate_table(plan3, "smoke", prev, "prev.json");
    CHECK(e.total_s == Approx(3 * (100 + 300 + 1000 + 3000) + 6));
  }
}

TEST_CASE("an estimate from another table or scale is refused", "[harness][estimate]") {
  const Json prev = test::fake_results();
  const auto plan = harness::plan_table(test::fake_options(), test::fake_hooks());
  CHECK_THROWS_WITH(harness::estimate_table(plan, "quick", prev, "prev.json"),
                    Catch::Contains("prev.json") && Catch::Contains("'quick'"));
  Json other = prev;
  other["table"] = "kitti360-low";
  CHECK_THROWS_WITH(harness::estimate_table(plan, "smoke", other, "x.json"),
                    Catch::Contains("kitti360-low"));
}

TEST_CASE("durations print in the unit a person reads", "[harness][estimate]") {
  CHECK(harness::format_duration(40) == "40 s");
  CHECK(harness::format_duration(14 * 60) == "14 min");
  CHECK(harness::format_duration(2 * 3600 + 5 * 60) == "2 h 05 min");
}
