// Tables of several seeds made by `sgnlf merge` (harness/combine.hpp, results/schema.md
// "Combined tables" and "Several seeds"): one-seed inputs of different seeds combine per cell
// (row × sequence × seed) into the entry `bench --seeds` writes; a row whose sequences ran
// different seeds; a conflicting run of one seed refused without --later-wins; the markdown, the
// README's summary and the claims with their spread; compare of a one-seed cell against a
// two-seed table using that spread; the run files and the plan per seed. Fake hooks, no training.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/config.hpp"
#include "fake_table.hpp"
#include "harness/cells.hpp"
#include "harness/claims.hpp"
#include "harness/combine.hpp"
#include "harness/compare.hpp"
#include "harness/markdown.hpp"
#include "harness/results.hpp"
#include "harness/run_files.hpp"
#include "harness/summary_table.hpp"
#include "harness/tables_plan_page.hpp"

using namespace sgnlf;
namespace fs = std::filesystem;

namespace {

using Inputs = std::vector<std::pair<std::string, Json>>;

// The fake kitti360-standard smoke table at `seeds`, with a spread over seeds (seed s adds
// 0.01 (s − 1) to cd and depth_psnr), rows and sequences as given (all when empty).
Json run(std::vector<uint64_t> seeds, std::vector<std::string> rows = {},
         std::vector<std::string> seqs = {}) {
  auto o = test::fake_options(std::move(seeds));
  o.rows = std::move(rows);
  o.sequences = std::move(seqs);
  return Json::parse(
      harness::run_table(o, test::fake_hooks(nullptr, false, true), test::fake_context()).dump());
}

// No current config hash (the fake's configs carry their seed, so no one hash is every seed's):
// nothing is stale, the plan's committed cells are done.
harness::BenchHooks hooks() {
  auto h = test::fake_hooks();
  h.config_hash = [](const std::string&, const std::string&) { return std::string(); };
  return h;
}

Json combine(const Inputs& in, bool later_wins = false) {
  return harness::combine_tables(in, harness::CombineOptions{later_wins}, hooks(), "sgnlf merge", "/o");
}

// A run entry as `comparable_view` compares it (times, paths aside), without the provenance a
// combined table adds (`source`, `stale`, also in each seed's run).
Json comparable(Json e) {
  for (const char* k : {"source", "stale"}) e.erase(k);
  if (e.contains("runs"))
    for (auto& x : e["runs"]) x.erase("source");
  const Json wrapped{{"rows", Json::array({Json{{"sequences", Json::array({e})}}})}};
  return harness::comparable_view(wrapped)["rows"][0]["sequences"][0];
}

const Json& entry(Json& r, const std::string& method, const std::string& seq) {
  for (const auto& e : test::row(r, method)["sequences"])
    if (e["sequence"] == seq) return e;
  throw std::out_of_range("no entry " + method + " / " + seq);
}

struct TempRoot {
  fs::path dir;
  explicit TempRoot(const std::string& name) : dir(fs::temp_directory_path() / ("sgnlf-" + name)) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~TempRoot() { fs::remove_all(dir); }
};

}  // namespace

TEST_CASE("merge of a seed-1 and a seed-2 table is the table bench --seeds 1,2 writes",
          "[harness][combine][seeds]") {
  Json s1 = run({1}), s2 = run({2});
  REQUIRE(s1["config"]["seed"] == 1);
  Json c = combine({{"s1/results.json", s1}, {"s2/results.json", s2}});
  Json full = run({1, 2});
  CHECK(c["config"]["seeds"] == Json::array({1, 2}));
  CHECK_FALSE(c["config"].contains("seed"));
  CHECK(c["seeds"]["table_seeds"] == Json::array({1, 2}));
  CHECK(c["seeds"]["runs"].size() == full["seeds"]["runs"].size());
  for (const char* m : {"lidar-nerf", "sg-nlf"}) {
    INFO(m);
    Json& row = test::row(c, m);
    // Row means and spread to the last bit, and every cell's entry as bench's.
    for (const char* k : {"mean", "mean_sd", "mean_by_seed", "diff_vs_paper"})
      CHECK(row[k] == test::row(full, m)[k]);
    for (const char* seq : {"kitti360-1538", "kitti360-1728"}) {
      INFO(seq);
      CHECK(comparable(entry(c, m, seq)) == comparable(entry(full, m, seq)));
      // Each seed's run names its own input; the entry names its first seed's.
      const Json& e = entry(c, m, seq);
      CHECK(e["runs"][0]["source"] == 0);
      CHECK(e["runs"][1]["source"] == 1);
      CHECK(e["source"] == 0);
      CHECK(e["stale"].is_null());
    }
    CHECK(row["sources"] == Json::array({0, 1}));
  }
  // The merged table merges again unchanged (a refresh), and the other input order gives seeds
  // 2, 1 in that order.
  Json again = combine({{"t/results.json", c}});
  CHECK(again["rows"] == c["rows"]);
  Json other = combine({{"s2/results.json", s2}, {"s1/results.json", s1}});
  CHECK(other["config"]["seeds"] == Json::array({2, 1}));
  CHECK(entry(other, "sg-nlf", "kitti360-1538")["seeds"] == Json::array({2, 1}));
  // A several-seed input and a third seed's: the runs join per cell.
  Json three = combine({{"f", full}, {"s3", run({3})}});
  CHECK(entry(three, "lidar-nerf", "kitti360-1728")["seeds"] == Json::array({1, 2, 3}));
  CHECK(test::row(three, "lidar-nerf")["mean"]["cd"].get<double>() == Approx(0.12));
  CHECK(test::row(three, "lidar-nerf")["mean_sd"]["cd"].get<double>() == Approx(0.01));
}

TEST_CASE("a row whose sequences ran different seeds: mean of seed means, sd over shared seeds",
          "[harness][combine][seeds]") {
  // lidar-nerf seed 1 on both sequences, seed 2 on kitti360-1538 only. cd per run: 0.1 + 0.02 k
  // + 0.01 (s − 1), k the sequence.
  Json c = combine({{"s1", run({1}, {"lidar-nerf"})}, {"s2", run({2}, {"lidar-nerf"}, {"kitti360-1538"})}});
  Json& row = test::row(c, "lidar-nerf");
  const Json& a = entry(c, "lidar-nerf", "kitti360-1538");
  const Json& b = entry(c, "lidar-nerf", "kitti360-1728");
  CHECK(a["seeds"] == Json::array({1, 2}));
  CHECK(a["metrics"]["cd"].get<double>() == Approx(0.105));
  CHECK(a["metrics_sd"]["cd"].get<double>() == Approx(0.01 / std::sqrt(2.0)));
  CHECK_FALSE(b.contains("runs"));  // a cell with one seed stays a one-seed entry
  CHECK(b["seed"] == 1);
  CHECK(row["mean"]["cd"].get<double>() == Approx((0.105 + 0.12) / 2));
  CHECK_FALSE(row.contains("mean_sd"));  // one seed shared by every sequence: no spread
  CHECK_FALSE(row.contains("mean_by_seed"));
  std::string md = harness::render_markdown(c);
  CHECK_THAT(md, Catch::Contains("seeds 1, 2, "));
  CHECK_THAT(md, Catch::Contains("| LiDAR-NeRF (seeds 1, 2 on 1 of 2 sequences) | 0.1125 |"));
  CHECK_THAT(md, Catch::Contains("| LiDAR-NeRF (seeds 1, 2) | 0.1050 ± 0.0071 |"));  // per sequence
  CHECK_THAT(md, Catch::Contains("| SG-NLF | not run |"));
  CHECK_THAT(md, Catch::Contains("| ok | kitti360-1538 [seed 1: 0, seed 2: 1], kitti360-1728 [0] |"));

  // Seeds 1 and 2 on both, seed 3 on kitti360-1538: the mean of each sequence's seed mean;
  // spread and per-seed means over the seeds 1 and 2 both have.
  c = combine({{"f", run({1, 2}, {"lidar-nerf"})}, {"s3", run({3}, {"lidar-nerf"}, {"kitti360-1538"})}});
  Json& r3 = test::row(c, "lidar-nerf");
  CHECK(r3["mean"]["cd"].get<double>() == Approx((0.11 + 0.125) / 2));
  REQUIRE(r3["mean_by_seed"].size() == 2);
  CHECK(r3["mean_by_seed"][1]["seed"] == 2);
  CHECK(r3["mean_by_seed"][1]["mean"]["cd"].get<double>() == Approx(0.12));
  CHECK(r3["mean_sd"]["cd"].get<double>() == Approx(0.01 / std::sqrt(2.0)));
  md = harness::render_markdown(c);
  CHECK_THAT(md, Catch::Contains("| LiDAR-NeRF (seeds 1, 2, 3 on 1 of 2 sequences) | 0.1175 ± 0.0071 |"));
}

TEST_CASE("a cell's seed run twice with different numbers is refused without --later-wins",
          "[harness][combine][seeds]") {
  const Json s1 = run({1}, {"lidar-nerf"}), s2 = run({2}, {"lidar-nerf"});
  Json s2b = s2;
  test::row(s2b, "lidar-nerf")["sequences"][0]["metrics"]["cd"] = 0.5;
  CHECK_THROWS_WITH(combine({{"s1", s1}, {"a/results.json", s2}, {"b/results.json", s2b}}),
                    Catch::Contains("lidar-nerf / kitti360-1538 / seed 2 is in both a/results.json "
                                    "and b/results.json with different results") &&
                        Catch::Contains("--later-wins"));
  // The same seed-2 runs again (a rerun that reproduced them) and seed 1 beside them: fine.
  Json same = combine({{"s1", s1}, {"a", s2}, {"a2", Json::parse(s2.dump())}});
  CHECK(same["combined_from"]["reproduced"].size() == 2);
  CHECK(same["combined_from"]["reproduced"][0]["seed"] == 2);
  // --later-wins: only that seed of that cell is replaced.
  Json c = combine({{"s1", s1}, {"a", s2}, {"b", s2b}}, true);
  REQUIRE(c["combined_from"]["superseded"].size() == 1);
  CHECK(c["combined_from"]["superseded"][0] ==
        Json{{"method", "lidar-nerf"}, {"sequence", "kitti360-1538"}, {"seed", 2}, {"source", 1}, {"by", 2}});
  const Json& e = entry(c, "lidar-nerf", "kitti360-1538");
  CHECK(e["runs"][0]["metrics"]["cd"].get<double>() == Approx(0.1));
  CHECK(e["runs"][1]["metrics"]["cd"] == 0.5);
  CHECK(e["runs"][1]["source"] == 2);
  CHECK_THAT(harness::render_markdown(c), Catch::Contains("lidar-nerf / kitti360-1538 / seed 2: source [1] replaced by [2]"));
}

TEST_CASE("two seeds in the tables: table.md, the README summary and the claims show the spread",
          "[harness][combine][seeds][summary]") {
  Json c = combine({{"s1", run({1})}, {"s2", run({2}, {"sg-nlf"})}});
  // lidar-nerf seed 1 alone, sg-nlf seeds 1 and 2 on both sequences: sg-nlf cd per seed s
  // 0.055 + 0.01 (s − 1): mean 0.06, sd 0.0071.
  const std::string md = harness::render_markdown(c);
  CHECK_THAT(md, Catch::Contains("except where a row or sequence is marked with its seeds"));
  CHECK_THAT(md, Catch::Contains("| SG-NLF (seeds 1, 2) | 0.0600 ± 0.0071 |"));
  CHECK_THAT(md, Catch::Contains("| LiDAR-NeRF | 0.1100 |"));
  const std::string sum = harness::summary_markdown(c, "t/table.md");
  CHECK_THAT(sum, Catch::Contains("| SG-NLF (seeds 1, 2) | 0.060 ± 0.0071 |"));
  CHECK_THAT(sum, Catch::Contains("| LiDAR-NeRF | 0.110 |"));
  // bench --seeds' own table needs no marks: every cell has every seed.
  const std::string all = harness::render_markdown(run({1, 2}));
  CHECK_THAT(all, Catch::Contains("| SG-NLF | 0.0600 ± 0.0071 |"));
  // A claim over the merged table: ours from the seed means, and per seed the rows' runs of it.
  harness::Claim claim{"SG-NLF vs LiDAR-NeRF, CD", "kitti360-standard", "cd", "sg-nlf", "lidar-nerf", -0.5, "", ""};
  const Json ch = harness::claim_change(claim, c);
  CHECK(ch["change"].get<double>() == Approx(0.06 / 0.11 - 1));
  CHECK(harness::claim_change_of_seed(claim, c, 1)["change"].get<double>() == Approx(0.055 / 0.11 - 1));
  CHECK(harness::claim_change_of_seed(claim, c, 2)["change"].is_null());  // lidar-nerf has no seed 2
  CHECK(harness::table_seeds(c) == std::vector<uint64_t>{1, 2});
}

TEST_CASE("compare: a one-seed cell against a two-seed table uses the table's spread",
          "[harness][compare][seeds]") {
  const Json base = combine({{"s1", run({1})}, {"s2", run({2})}});
  // A fresh run of one cell (bench --rows lidar-nerf --sequences kitti360-1538 --seed 1).
  const Json cell = run({1}, {"lidar-nerf"}, {"kitti360-1538"});
  harness::CompareOptions opt;
  opt.subset = true;
  opt.timings = false;
  opt.mode = "loose";  // as a quick table on another device (auto holds a smoke table tight)
  auto rep = harness::compare_results(cell, base, opt);
  INFO(harness::format_report(rep));
  CHECK_FALSE(rep.regression());
  CHECK(rep.seed_spread_used > 0);
  // Baseline cd 0.105 ± 0.00707 (2 seeds); the single run is one more draw: allowance
  // tolerance + 2 · sd · √(1 + 1/2).
  const double tol = harness::metric_tolerance("cd", "loose", 0.105);
  const double spread = 2 * (0.01 / std::sqrt(2.0)) * std::sqrt(1.5);
  Json within = cell, beyond = cell;
  test::row(within, "lidar-nerf")["sequences"][0]["metrics"]["cd"] = 0.105 + tol + 0.5 * spread;
  test::row(beyond, "lidar-nerf")["sequences"][0]["metrics"]["cd"] = 0.105 + tol + 1.5 * spread;
  CHECK_FALSE(harness::compare_results(within, base, opt).regression());
  rep = harness::compare_results(beyond, base, opt);
  CHECK(rep.regression());
  bool cd_named = false;
  for (const auto& f : rep.findings)
    cd_named |= f.fails && f.where == "lidar-nerf / kitti360-1538 / cd" &&
                f.message.find("seed standard error (1 vs 2 seeds)") != std::string::npos;
  CHECK(cd_named);
  // Tight (chosen): the one-seed run is the twin of the baseline's run of its seed.
  opt.mode = "tight";
  rep = harness::compare_results(cell, base, opt);
  INFO(harness::format_report(rep));
  CHECK_FALSE(rep.regression());
  CHECK(harness::compare_results(within, base, opt).regression());
  const Json seed3 = run({3}, {"lidar-nerf"}, {"kitti360-1538"});
  rep = harness::compare_results(seed3, base, opt);
  CHECK(rep.regression());  // the baseline has no seed 3 of that cell
  // A whole row at seed 2, tight, against the baseline's seed-2 mean.
  CHECK_FALSE(harness::compare_results(run({2}, {"lidar-nerf"}), base, opt).regression());
}

TEST_CASE("merge --keep-run-files and the plan, per seed", "[harness][combine][seeds][plan]") {
  TempRoot root("merge-seeds");
  // Two bench outputs, seeds 1 and 2, moved from their out_dir to root/sK: their run folders are
  // found under each file's folder.
  Inputs in;
  for (uint64_t k : {1, 2}) {
    const Json r = run({k}, {"lidar-nerf"});
    const fs::path file = root.dir / ("s" + std::to_string(k)) / "results.json";
    fs::create_directories(file.parent_path());
    write_json_file(file.string(), r);
    for (const char* seq : {"kitti360-1538", "kitti360-1728"})
      for (const auto& name : harness::kept_run_file_names()) {
        const fs::path p = file.parent_path() / "runs" / "lidar-nerf" / seq / name;
        fs::create_directories(p.parent_path());
        write_text_file(p.string(), "seed " + std::to_string(k) + "\n");
      }
    in.push_back({file.string(), r});
  }
  const fs::path out = root.dir / "tables" / "kitti360-standard" / "smoke";
  const Json merged = harness::combine_tables(in, {}, hooks(), "sgnlf merge", out.string());
  const auto kept = harness::keep_run_files(merged, in, out.string());
  CHECK(kept.copied.size() == 2 * 2 * harness::kept_run_file_names().size());
  std::string text;
  std::ifstream f(out / "runs/lidar-nerf/kitti360-1728/seed2/metrics.json");
  std::getline(f, text);
  CHECK(text == "seed 2");
  // The plan reads both seeds' cells from the one merged table.
  write_json_file((out / "results.json").string(), merged);
  const Json plan{{"scale", "smoke"}, {"seeds", {1, 2}}, {"roots", {"."}}};
  const fs::path tables = root.dir / "tables";
  write_json_file(harness::plan_json_path(tables.string()), plan);
  const auto p = harness::derive_tables_plan(
      tables.string(), harness::parse_tables_plan_file(plan, "plan.json"), hooks(), "plan.json");
  size_t done = 0;
  for (const auto& t : p.tables)
    for (const auto& c : t.cells)
      if (t.name == "kitti360-standard" && c.ref.row == "lidar-nerf") {
        CHECK(c.committed);
        CHECK(c.run_files);
        CHECK(c.results == "kitti360-standard/smoke/results.json");
        done += c.state == "done";
      }
  CHECK(done == 4);  // 2 sequences × 2 seeds
}

TEST_CASE("a claim over a stale row is marked, not judged", "[harness][claims]") {
  Json t{{"rows", Json::array({Json{{"method", "sg-nlf"}, {"stale", false},
                                    {"sequences", Json::array({Json{{"sequence", "a"}, {"stale", false}},
                                                               Json{{"sequence", "b"}, {"stale", true}}})}},
                               Json{{"method", "geonlf"}, {"stale", false},
                                    {"sequences", Json::array({Json{{"sequence", "a"}, {"stale", false}}})}},
                               Json{{"method", "lidar4d"}, {"stale", true}, {"sequences", Json::array()}}})}};
  CHECK(harness::claim_row_stale(t, "sg-nlf"));      // one stale sequence
  CHECK_FALSE(harness::claim_row_stale(t, "geonlf"));
  CHECK(harness::claim_row_stale(t, "lidar4d"));     // the row's flag
  CHECK_FALSE(harness::claim_row_stale(t, "lidar-nerf"));  // no such row
  t["rows"][0]["sequences"][1]["stale"] = false;
  CHECK_FALSE(harness::claim_row_stale(t, "sg-nlf"));
}

TEST_CASE("a claim over rows scored by different evaluation rules is marked, not judged",
          "[harness][claims]") {
  const auto run = [](const Json& render) {
    return Json{{"config", {{"method", "x"}, {"render", render}}}};
  };
  Json t{{"rows", Json::array({
      Json{{"method", "sg-nlf"},
           {"sequences", Json::array({Json{{"sequence", "a"},
                                           {"runs", Json::array({run({{"eval_depth", "mix"},
                                                                      {"eval_drop_out_of_range", true}}),
                                                                 run({{"eval_depth", "mix"},
                                                                      {"eval_drop_out_of_range", true}})})}}})}},
      Json{{"method", "lidar4d"},
           {"sequences", Json::array({run(Json::object()), run({{"n_samples", 64}})})}},
      Json{{"method", "geonlf"},
           {"sequences", Json::array({run({{"eval_depth", "mix"}, {"eval_drop_out_of_range", true}}),
                                      run({{"eval_depth", "median"}})})}},
      Json{{"method", "old"}, {"sequences", Json::array({Json{{"sequence", "a"}}})}}})}};
  CHECK(harness::claim_row_rules(t, "sg-nlf") == "mix depth, out-of-range drops");
  CHECK(harness::claim_row_rules(t, "lidar4d") == "expected depth");  // the config's default
  CHECK(harness::claim_row_rules(t, "geonlf") == "mix depth, out-of-range drops / median depth");
  CHECK(harness::claim_row_rules(t, "old").empty());    // no config recorded
  CHECK(harness::claim_row_rules(t, "none").empty());   // no such row
}
