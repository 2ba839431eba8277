// Tables combined from partial runs (`sgnlf merge` of results.json files, harness/combine.hpp)
// and the committed-table check (harness/table_check.hpp). Fake hooks, no training: partial
// runs of the fake kitti360-standard smoke table (rows / sequences subsets) are combined and
// compared with the full run, and every refusal and flag is made to happen.
#include <catch2/catch.hpp>

#include "core/config.hpp"
#include "fake_table.hpp"
#include "harness/cells.hpp"
#include "harness/combine.hpp"
#include "harness/markdown.hpp"
#include "harness/results.hpp"
#include "harness/table_check.hpp"

using namespace sgnlf;

namespace {

using Inputs = std::vector<std::pair<std::string, Json>>;

// A run of the fake table with a row (and sequence) subset, as written and read back.
Json partial(std::vector<std::string> rows, std::vector<std::string> seqs = {},
             bool seed_noise = false, std::vector<uint64_t> seeds = {}) {
  auto o = test::fake_options(std::move(seeds));
  o.rows = std::move(rows);
  o.sequences = std::move(seqs);
  return Json::parse(
      harness::run_table(o, test::fake_hooks(nullptr, false, seed_noise), test::fake_context()).dump());
}

// The fake hooks, plus a current config hash per method: the fake runs' own for lidar-nerf
// (not stale), another for sg-nlf (stale), none for the rows the fake does not implement.
harness::BenchHooks hooks(bool sg_nlf_stale = true) {
  auto h = test::fake_hooks();
  h.config_hash = [sg_nlf_stale](const std::string& m, const std::string&) -> std::string {
    if (m != "lidar-nerf" && m != "sg-nlf") return "";
    if (m == "sg-nlf" && sg_nlf_stale) return "00000000000000ff";
    return harness::config_hash(Json{{"method", m}, {"iterations", 10}, {"seed", 7}});
  };
  return h;
}

Json combine(const Inputs& in, bool later_wins = false, const harness::BenchHooks& h = hooks()) {
  return harness::combine_tables(in, harness::CombineOptions{later_wins}, h, "sgnlf merge", "/o");
}

}  // namespace

TEST_CASE("partial runs combine into every row of the table, with provenance",
          "[harness][combine]") {
  const Json a = partial({"lidar-nerf"}), b = partial({"sg-nlf"});
  Json c = combine({{"a/results.json", a}, {"b/results.json", b}});
  Json full = test::fake_results();
  REQUIRE(c["rows"].size() == full["rows"].size());
  CHECK(test::row(c, "lidar-nerf")["status"] == "ok");
  CHECK(test::row(c, "sg-nlf")["status"] == "ok");
  CHECK(test::row(c, "lidar4d")["status"] == "not_implemented");  // the fake lacks it
  // The numbers are the full run's.
  CHECK(test::row(c, "lidar-nerf")["mean"] == test::row(full, "lidar-nerf")["mean"]);
  CHECK(test::row(c, "sg-nlf")["mean"] == test::row(full, "sg-nlf")["mean"]);
  // Each run names its source; sources carry command, commit and time.
  REQUIRE(c["combined_from"]["files"].size() == 2);
  CHECK(c["combined_from"]["files"][1]["file"] == "b/results.json");
  CHECK(c["combined_from"]["files"][1]["git"]["sha"] == test::fake_context()["git"]["sha"]);
  CHECK(c["combined_from"]["files"][1]["command"] == b["command"]);
  CHECK(test::row(c, "sg-nlf")["sequences"][1]["source"] == 1);
  CHECK(test::row(c, "lidar-nerf")["sources"] == Json::array({0}));
  CHECK(c["config"].contains("rows") == false);
  CHECK(c["sequences"].size() == 2);
  CHECK(c["seeds"]["runs"].size() == 4);
  // A row the build implements but no input ran is "not run", not "not implemented".
  auto h = hooks();
  h.implemented = [](const std::string& m) { return m != "lidar4d"; };
  c = combine({{"a/results.json", a}}, false, h);
  CHECK(test::row(c, "sg-nlf")["status"] == "not_run");
  CHECK(test::row(c, "lidar4d")["status"] == "not_implemented");
  CHECK(test::row(c, "geonlf")["sequences_not_run"].size() == 2);
  const std::string md = harness::render_markdown(c);
  CHECK_THAT(md, Catch::Contains("| not run |"));
  CHECK_THAT(md, Catch::Contains("not implemented"));
  CHECK_THAT(md, Catch::Contains("## Provenance"));
}

TEST_CASE("a run made with another config than today's is flagged stale", "[harness][combine]") {
  Json c = combine({{"a", partial({"lidar-nerf"})}, {"b", partial({"sg-nlf"})}});
  CHECK(test::row(c, "lidar-nerf")["stale"] == false);
  CHECK(test::row(c, "lidar-nerf")["sequences"][0]["stale"] == false);
  CHECK(test::row(c, "sg-nlf")["stale"] == true);
  CHECK(test::row(c, "sg-nlf")["sequences"][1]["stale"] == true);
  CHECK(test::row(c, "sg-nlf")["current_config_hash"] == "00000000000000ff");
  CHECK(test::row(c, "geonlf")["stale"].is_null());
  const std::string md = harness::render_markdown(c);
  CHECK_THAT(md, Catch::Contains("(stale config) |"));
  CHECK_THAT(md, Catch::Contains("**stale**"));
  c = combine({{"b", partial({"sg-nlf"})}}, false, hooks(false));
  CHECK(test::row(c, "sg-nlf")["stale"] == false);
}

TEST_CASE("a row run on some sequences is partial; the rest are not run", "[harness][combine]") {
  Json cc = combine({{"a", partial({"sg-nlf"}, {"kitti360-1538"})}});
  CHECK(test::row(cc, "sg-nlf")["status"] == "ok");
  CHECK(test::row(cc, "sg-nlf")["sequences"].size() == 1);
  CHECK(test::row(cc, "sg-nlf")["sequences_not_run"] == Json::array({"kitti360-1728"}));
  REQUIRE(cc["skipped_sequences"].size() == 1);  // no row ran it
  CHECK(cc["skipped_sequences"][0]["name"] == "kitti360-1728");
  const std::string md = harness::render_markdown(cc);
  CHECK_THAT(md, Catch::Contains("(partial: 1 of 2 sequences)"));
  CHECK_THAT(md, Catch::Contains("Sequence kitti360-1728 not run:"));
}

TEST_CASE("conflicting runs of a cell are refused unless the later input wins",
          "[harness][combine]") {
  Json a = test::fake_results(), b = partial({"lidar-nerf"}, {}, true);
  Json a2 = Json::parse(test::fake_results().dump());
  // Equal duplicates (times and paths aside) are one run, recorded as reproduced: the first
  // input's, or with --later-wins the later one's provenance (a clean rerun certifying a cell).
  Json eq;
  REQUIRE_NOTHROW(eq = combine({{"a", a}, {"a2", a2}}));
  size_t cells = 0;
  for (const auto& row : a["rows"]) cells += row.value("sequences", Json::array()).size();
  CHECK(cells > 0);
  CHECK(eq["combined_from"]["reproduced"].size() == cells);
  CHECK(eq["combined_from"]["superseded"].empty());
  CHECK(test::row(eq, "lidar-nerf")["sources"] == Json::array({0}));
  CHECK(eq["combined_from"]["reproduced"][0]["by"] == 1);
  Json eq_later = combine({{"a", a}, {"a2", a2}}, true);
  CHECK(test::row(eq_later, "lidar-nerf")["sources"] == Json::array({1}));
  CHECK(test::row(eq_later, "lidar-nerf")["mean"] == test::row(eq, "lidar-nerf")["mean"]);
  CHECK(eq_later["combined_from"]["superseded"].empty());
  CHECK_THROWS_WITH(combine({{"first/results.json", a}, {"second/results.json", b}}),
                    Catch::Contains("lidar-nerf / kitti360-1538 / seed 7 is in both first/results.json and "
                                    "second/results.json") &&
                        Catch::Contains("--later-wins"));
  Json c = combine({{"a", a}, {"b", b}}, true);
  CHECK(test::row(c, "lidar-nerf")["mean"] == test::row(b, "lidar-nerf")["mean"]);
  CHECK(test::row(c, "lidar-nerf")["sources"] == Json::array({1}));
  CHECK(test::row(c, "sg-nlf")["sources"] == Json::array({0}));
  CHECK(c["combined_from"]["superseded"].size() == 2);
  // The other order: a wins.
  c = combine({{"b", b}, {"a", a}}, true);
  CHECK(test::row(c, "lidar-nerf")["mean"] == test::row(a, "lidar-nerf")["mean"]);
}

TEST_CASE("combining refuses other tables, scales and unknown rows", "[harness][combine]") {
  const Json a = partial({"lidar-nerf"});
  Json other = a;
  other["scale"] = "quick";
  CHECK_THROWS_WITH(combine({{"a", a}, {"o", other}}), Catch::Contains("a and o are of different scale"));
  // Other seeds are not refused: they join per cell (test_merge_seeds.cpp).
  CHECK(combine({{"a", a}, {"s", partial({"sg-nlf"}, {}, false, {1, 2})}})["config"]["seeds"] ==
        Json::array({7, 1, 2}));
  Json renamed = a;
  test::row(renamed, "lidar-nerf")["method"] = "old-method";
  CHECK_THROWS_WITH(combine({{"r", renamed}}), Catch::Contains("row 'old-method' is not a row"));
  Json seq = a;
  test::row(seq, "lidar-nerf")["sequences"][0]["sequence"] = "gone";
  CHECK_THROWS_WITH(combine({{"q", seq}}), Catch::Contains("ran sequence 'gone'"));
  CHECK_THROWS_WITH(combine({{"c", Json{{"schema", "sgnlf.cell"}}}}), Catch::Contains("c is not an"));
}

TEST_CASE("a combined table combines again: sources and flags carried", "[harness][combine]") {
  const Json c = combine({{"a", partial({"lidar-nerf"})}, {"b", partial({"sg-nlf"})}});
  Json again = combine({{"tables/x/results.json", c}});
  CHECK(again["combined_from"]["files"] == c["combined_from"]["files"]);
  CHECK(again["rows"] == c["rows"]);
  // A new several-seed-free run added later replaces sg-nlf with --later-wins only.
  const Json fresh = partial({"sg-nlf"}, {}, true);
  Json c2 = Json::parse(fresh.dump());
  c2["context"]["git"]["sha"] = "fedcba";
  CHECK_THROWS(combine({{"t", c}, {"n", c2}}));  // seed 7 with noise: different numbers
  again = combine({{"t", c}, {"n", c2}}, true);
  CHECK(again["combined_from"]["files"].size() == 3);
  CHECK(test::row(again, "sg-nlf")["sources"] == Json::array({2}));
}

TEST_CASE("several seeds combine per sequence", "[harness][combine]") {
  const Json a = partial({"lidar-nerf"}, {}, true, {1, 2}), b = partial({"sg-nlf"}, {}, true, {1, 2});
  Json c = combine({{"a", a}, {"b", b}});
  auto o = test::fake_options({1, 2});
  Json full = harness::run_table(o, test::fake_hooks(nullptr, false, true), test::fake_context());
  CHECK(test::row(c, "sg-nlf")["mean"] == test::row(full, "sg-nlf")["mean"]);
  CHECK(test::row(c, "sg-nlf")["mean_sd"] == test::row(full, "sg-nlf")["mean_sd"]);
  CHECK(test::row(c, "sg-nlf")["sequences"][0]["runs"].size() == 2);
  CHECK(c["seeds"]["table_seeds"] == Json::array({1, 2}));
}

TEST_CASE("committed tables are checked against the table definition and their markdown",
          "[harness][combine][check-tables]") {
  auto h = hooks();
  Json c = combine({{"a", partial({"lidar-nerf"})}, {"b", partial({"sg-nlf"})}});
  const std::string md = harness::render_markdown(c);
  const auto check = [&](const Json& r, const std::string& text = "") {
    return harness::check_committed_table(r, text.empty() ? harness::render_markdown(r) : text,
                                          "kitti360-standard", "smoke", h);
  };
  CHECK(check(c, md).empty());
  // A full one-process run is a committed table as it is.
  CHECK(check(test::fake_results()).empty());
  // Each difference is found.
  CHECK(!harness::check_committed_table(c, md, "kitti360-low", "smoke", h).empty());
  CHECK(!harness::check_committed_table(c, md, "kitti360-standard", "quick", h).empty());
  CHECK_THAT(check(c, md + "edited\n").at(0), Catch::Contains("table.md is not the rendering"));
  Json fewer = c;
  fewer["rows"].erase(fewer["rows"].size() - 1);
  CHECK_THAT(check(fewer).at(0), Catch::Contains("rows are ["));
  Json relabel = c;
  test::row(relabel, "sg-nlf")["label"] = "old";
  CHECK_THAT(check(relabel).at(0), Catch::Contains("label 'old'"));
  Json frames = c;
  frames["sequences"][0]["frames"] = 99;
  CHECK_THAT(check(frames).at(0), Catch::Contains("frames is 99"));
  Json noseq = c;
  noseq["skipped_sequences"] = Json::array();
  noseq["sequences"].erase(1);
  CHECK(!check(noseq).empty());
  CHECK_THAT(check(partial({"sg-nlf"})).at(0), Catch::Contains("left out by --rows"));
  Json notimpl = c;
  test::row(notimpl, "sg-nlf")["status"] = "not_implemented";
  CHECK(!check(notimpl).empty());
  // The stale flags are this build's: a preset that moved makes the committed table differ.
  h = hooks(false);
  CHECK_THAT(check(c, md).at(0), Catch::Contains("current_config_hash"));
  Json refreshed = combine({{"t", c}}, false, h);
  CHECK(check(refreshed).empty());
}

TEST_CASE("provenance names the binary's build when it differs from the checkout's state",
          "[harness][combine]") {
  Json a = partial({"lidar-nerf"});
  a["context"]["git"] = Json{{"sha", "aaaaaaa1111"}, {"dirty", true}};
  a["context"]["build"]["git"] = Json{{"sha", "aaaaaaa1111"}, {"dirty", false}};
  Json b = partial({"sg-nlf"});
  b["context"]["git"] = Json{{"sha", "bbbbbbb2222"}, {"dirty", false}};
  b["context"]["build"]["git"] = Json{{"sha", "bbbbbbb2222"}, {"dirty", false}};
  const Json c = combine({{"a/results.json", a}, {"b/results.json", b}});
  CHECK(c["combined_from"]["files"][0]["build_git_dirty"] == false);
  const std::string md = harness::render_markdown(c);
  CHECK_THAT(md, Catch::Contains("`a/results.json`: commit aaaaaaa (dirty), binary of clean aaaaaaa,"));
  CHECK_THAT(md, Catch::Contains("`b/results.json`: commit bbbbbbb, "));  // nothing more to say
  // A binary built from another commit than the checkout's is named too.
  b["context"]["build"]["git"] = Json{{"sha", "ccccccc3333"}, {"dirty", true}};
  const std::string md2 = harness::render_markdown(combine({{"b/results.json", b}}));
  CHECK_THAT(md2, Catch::Contains("commit bbbbbbb, binary of dirty ccccccc,"));
}
