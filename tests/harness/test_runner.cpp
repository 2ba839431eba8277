// Table definitions, the table runner (with fake hooks) and the markdown renderer: means over
// sequences, differences to the paper, "not implemented" and "failed" rows kept in place; a
// real sequence inside a synthetic scale (skipped when its folder is missing, else averaged
// apart from the twins).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "core/config.hpp"
#include "fake_table.hpp"
#include "harness/compare.hpp"
#include "harness/markdown.hpp"
#include "harness/results.hpp"
#include "harness/schema.hpp"
#include "harness/tables.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;

TEST_CASE("every table parses and its columns and paper numbers are consistent", "[harness]") {
  const auto names = harness::table_names();
  REQUIRE(names.size() == 5);
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

TEST_CASE("markdown: the horizontal ATE beside the 3D one, blank where a run lacks it",
          "[harness][ate_h]") {
  CHECK(harness::metric_info("ate_h_m") != nullptr);
  CHECK(harness::metric_info("ate_h_m")->lower_better);
  CHECK(harness::metric_tolerance("ate_h_m", "loose", 0.2) ==
        harness::metric_tolerance("ate_m", "loose", 0.2));
  for (const std::string t : {"kitti360-low", "nuscenes-low", "ablation-nuscenes"}) {
    const auto ex = harness::table_def(t).extra_columns;
    CHECK(std::find(ex.begin(), ex.end(), "ate_h_m") != ex.end());
  }
  // Runs made before ate_h_m (sg-nlf's fake runs report ate_m only, as the committed tables):
  // the column renders "—", and no sequence is said to have planar reference poses.
  Json r = test::fake_results();
  r["columns"] = {"cd"};
  r["extra_columns"] = {"ate_m", "ate_h_m"};
  std::string md = harness::render_markdown(r);
  CHECK(md.find("| ATE (m) ↓ | ATE horizontal (m) ↓ |") != std::string::npos);
  CHECK(md.find("| SG-NLF | 0.0550 | 0.0867 | -0.0317 | 0.0700 | — |") != std::string::npos);
  CHECK(md.find("| SG-NLF | 0.0500 | 0.0700 | — |") != std::string::npos);  // kitti360-1538
  CHECK(md.find("are planar") == std::string::npos);
  // A run that reports it, against planar reference poses: its number, and the sequence's note.
  for (auto& s : test::row(r, "sg-nlf")["sequences"])
    if (s["sequence"] == "kitti360-1538")
      s["pose_metrics"] = {{"ate_m", 0.07}, {"ate_h_m", 0.05}, {"ate_reference", "horizontal"}};
  md = harness::render_markdown(r);
  CHECK(md.find("| SG-NLF | 0.0500 | 0.0700 | 0.0500 |") != std::string::npos);
  CHECK(md.find("The reference poses of kitti360-1538 are planar") != std::string::npos);
  CHECK(md.find("The reference poses of kitti360-1728") == std::string::npos);
}

// --- A real sequence inside a synthetic scale (tables.json `real_dir`, nuscenes-low quick) ---

namespace {

// Hooks for nuscenes-low: only sg-nlf runs; its CD is 1, 2, 3 on the twins a, b, c and 100 on
// the real scene, so a real sequence leaking into the twins' mean shows. Every prepare call
// is logged as "name=data_root".
harness::BenchHooks real_seq_hooks(std::vector<std::string>* prepares) {
  harness::BenchHooks h = test::fake_hooks();
  h.implemented = [](const std::string& m) { return m == "sg-nlf"; };
  h.prepare = [prepares](const harness::SequenceDef& s, const harness::BenchOptions& o,
                         const std::string& dir) {
    prepares->push_back(s.name + "=" + o.data_root);
    harness::PreparedSequence p;
    p.dataset_dir = dir;
    p.dataset = Json{{"name", s.name}, {"frames", 36}, {"test", {4, 12, 20}}, {"seed", nullptr}};
    return p;
  };
  h.run = [](const pipeline::MethodRequest& r) {
    const std::string d = r.dataset_dir;
    const double cd = d.find("nuscenes-low-a") != std::string::npos   ? 1.0
                      : d.find("nuscenes-low-b") != std::string::npos ? 2.0
                      : d.find("nuscenes-low-c") != std::string::npos ? 3.0
                                                                      : 100.0;
    pipeline::MethodResult res;
    res.config = Json{{"method", r.method}};
    res.metrics = Json{{"cd", cd}, {"depth_rmse", 10.0 * cd}};
    res.pose_metrics = Json{{"ate_m", 0.01 * cd}};
    res.extra = Json{{"naive_baseline", {{"cd", cd + 0.5}}}};
    res.timings = Json{{"train", 1.0}};
    return res;
  };
  return h;
}

harness::BenchOptions nuscenes_quick(const std::string& real_root) {
  harness::BenchOptions o;
  o.table = "nuscenes-low";
  o.scale = "quick";
  o.out_dir = "/nonexistent/out";
  o.real_root = real_root;
  return o;
}

}  // namespace

TEST_CASE("tables: nuscenes-low carries the real scene and the ground-truth-pose control",
          "[harness]") {
  const auto t = harness::table_def("nuscenes-low");
  std::vector<std::string> methods;
  for (const auto& r : t.rows) methods.push_back(r.method);
  CHECK(methods == std::vector<std::string>{"geonlf", "geonlf-frozen", "sg-nlf", "sg-nlf-gt-poses"});
  CHECK(t.rows[3].label.find("ground-truth poses") != std::string::npos);
  for (const std::string scale : {"quick", "paper"}) {
    const auto seqs = harness::table_sequences(t, scale, false);
    REQUIRE(seqs.size() == 4);
    const auto& real = seqs.back();
    CHECK(real.name == "nuscenes-real-0916");
    CHECK(real.real_dir == "nuscenes-mini-scene-0916");
    CHECK(real.sequence == "scene-0916");
    CHECK(real.frames == 36);
    CHECK(real.to_json()["real_dir"] == "nuscenes-mini-scene-0916");
    for (size_t i = 0; i + 1 < seqs.size(); ++i) CHECK_FALSE(seqs[i].is_real_dir());
  }
  // The smoke scales (the CI baselines) and the --data-root lists have no real_dir sequence.
  for (const auto& n : harness::table_names()) {
    const auto d = harness::table_def(n);
    for (const auto& s : harness::table_sequences(d, "smoke", false)) {
      CHECK_FALSE(s.is_real_dir());
      CHECK_FALSE(s.to_json().contains("real_dir"));
    }
    for (const auto& s : d.real) CHECK_FALSE(s.is_real_dir());
  }
}

TEST_CASE("tables: real_dir is parsed and checked, unknown keys stay rejected", "[harness]") {
  const Json base{{"name", "x"}, {"preset", "nuscenes"}, {"frequency", "low"}};
  CHECK_FALSE(harness::parse_sequence_def(base, "t").is_real_dir());
  Json ok = base;
  ok["real_dir"] = "some-scene";
  CHECK(harness::parse_sequence_def(ok, "t").real_dir == "some-scene");
  for (const Json& bad : {Json(7), Json(true), Json::array({"a"}), Json(nullptr)}) {
    Json j = base;
    j["real_dir"] = bad;
    CHECK_THROWS_AS(harness::parse_sequence_def(j, "t"), ConfigError);
  }
  for (const std::string bad : {"", "/abs/scene", "../outside", "a/../../b"}) {
    Json j = base;
    j["real_dir"] = bad;
    CHECK_THROWS_WITH(harness::parse_sequence_def(j, "t"), Catch::Contains("real_dir"));
  }
  Json unknown = base;
  unknown["real_folder"] = "x";
  CHECK_THROWS_WITH(harness::parse_sequence_def(unknown, "t"), Catch::Contains("real_folder"));
}

TEST_CASE("kitti360-dynamic: LiDAR4D's dynamic set, its rows, scales and reference numbers", "[harness]") {
  const auto t = harness::table_def("kitti360-dynamic");
  REQUIRE(t.rows.size() == 2);
  CHECK(t.rows[0].method == "lidar-nerf");
  CHECK(t.rows[1].method == "lidar4d");
  CHECK(harness::table_sequences(t, "smoke", false).size() == 1);
  const auto quick = harness::table_sequences(t, "quick", false);
  CHECK((quick.size() >= 2 && quick.size() <= 4));
  const auto paper = harness::table_sequences(t, "paper", false), real = harness::table_sequences(t, "paper", true);
  REQUIRE(paper.size() == 6);
  REQUIRE(real.size() == 6);
  const int starts[] = {2350, 4950, 8120, 10200, 10750, 11400};
  for (size_t k = 0; k < 6; ++k) {
    CHECK(paper[k].name == "kitti360-dyn-" + std::to_string(starts[k]));
    CHECK(real[k].start == starts[k]);
    CHECK(real[k].frames == 51);
    CHECK(real[k].test_frames == std::vector<int>{10, 20, 30, 40});
  }
  // LiDAR4D's released numbers on the real dynamic set, and where they come from.
  const Json l4d = harness::paper_numbers("kitti360-dynamic", "lidar4d");
  CHECK(l4d["cd"] == 0.1002);
  CHECK(l4d["depth_rmse"] == 3.059);
  CHECK(l4d["depth_psnr"] == 28.75);
  CHECK(l4d["intensity_psnr"] == 20.09);
  const Json nerf = harness::paper_numbers("kitti360-dynamic", "lidar-nerf");
  CHECK(nerf["cd"] == 0.1438);
  CHECK(nerf["depth_rmse"] == 4.175);
  CHECK(nerf["depth_psnr"] == 25.99);
  CHECK(nerf["intensity_psnr"] == 17.15);
  CHECK_THAT(harness::paper_source("kitti360-dynamic"), Catch::Contains("LiDAR4D"));
  CHECK(harness::paper_source("kitti360-standard") == "protocol §5 (results/paper_tables.json)");
}

TEST_CASE("tables: test_frames are positions in the window, checked", "[harness]") {
  const Json base{{"name", "x"}, {"preset", "kitti360"}, {"frequency", "standard"}, {"frames", 51}};
  CHECK(harness::parse_sequence_def(base, "t").test_frames.empty());
  CHECK_FALSE(harness::parse_sequence_def(base, "t").to_json().contains("test_frames"));
  Json ok = base;
  ok["test_frames"] = {10, 20};
  CHECK(harness::parse_sequence_def(ok, "t").to_json()["test_frames"] == Json::array({10, 20}));
  for (const Json& bad : {Json::array({51}), Json::array({-1}), Json::array({3, 3}), Json::array({1.5}), Json("10")}) {
    Json j = base;
    j["test_frames"] = bad;
    CHECK_THROWS_WITH(harness::parse_sequence_def(j, "t"), Catch::Contains("test_frames"));
  }
}

TEST_CASE("run_table: a real sequence whose folder is missing is skipped and recorded",
          "[harness]") {
  const std::string root = test::temp_dir("harness-real-missing");  // empty: no scene in it
  std::vector<std::string> prepares;
  const Json r = harness::run_table(nuscenes_quick(root), real_seq_hooks(&prepares),
                                    test::fake_context());
  CHECK(prepares == std::vector<std::string>{"nuscenes-low-a=", "nuscenes-low-b=",
                                             "nuscenes-low-c="});
  REQUIRE(r["skipped_sequences"].size() == 1);
  const Json& sk = r["skipped_sequences"][0];
  CHECK(sk["name"] == "nuscenes-real-0916");
  CHECK(sk["path"] == root + "/nuscenes-mini-scene-0916");
  CHECK(sk["reason"].get<std::string>().find("real data not found at " + root) !=
        std::string::npos);
  CHECK(r["real_root"] == root);
  CHECK(r["sequences"].size() == 3);
  const Json& sg = r["rows"][2];
  REQUIRE(sg["status"] == "ok");
  CHECK(sg["sequences"].size() == 3);
  CHECK(sg["mean"]["cd"].get<double>() == Approx(2.0));
  CHECK_FALSE(sg.contains("mean_real"));
  CHECK(r["rows"][3]["method"] == "sg-nlf-gt-poses");
  CHECK(r["rows"][3]["status"] == "not_implemented");  // the fake hooks do not run it
  const std::string md = harness::render_markdown(r);
  CHECK(md.find("**Sequence nuscenes-real-0916 not run:** real data not found at") !=
        std::string::npos);
  CHECK(md.find("## Real data") == std::string::npos);
  // Named with --sequences, a missing real sequence is an error, not a silent skip.
  auto o = nuscenes_quick(root);
  o.sequences = {"nuscenes-real-0916"};
  CHECK_THROWS_WITH(o.validate(), Catch::Contains("real data not found"));
  o.sequences = {"nuscenes-low-a"};
  CHECK_NOTHROW(o.validate());
  o.real_root = root + "/nope";
  CHECK_THROWS_WITH(o.validate(), Catch::Contains("--real-root"));
}

TEST_CASE("run_table: a present real sequence runs from its folder, apart from the twins' mean",
          "[harness]") {
  const std::string root = test::temp_dir("harness-real-present");
  const std::string scene = root + "/nuscenes-mini-scene-0916";
  std::filesystem::create_directories(scene);
  std::vector<std::string> prepares;
  const Json r = harness::run_table(nuscenes_quick(root), real_seq_hooks(&prepares),
                                    test::fake_context());
  // Twins are simulated (no data root); the real scene is prepared from its resolved folder.
  CHECK(prepares == std::vector<std::string>{"nuscenes-low-a=", "nuscenes-low-b=",
                                             "nuscenes-low-c=", "nuscenes-real-0916=" + scene});
  CHECK(r["skipped_sequences"].empty());
  CHECK(r["data"] == "synthetic");
  REQUIRE(r["sequences"].size() == 4);
  CHECK(r["sequences"][3]["real_dir"] == "nuscenes-mini-scene-0916");
  CHECK(r["sequences"][3]["real_path"] == scene);
  CHECK_FALSE(r["sequences"][0].contains("real_dir"));
  const Json& sg = r["rows"][2];
  REQUIRE(sg["status"] == "ok");
  CHECK(sg["sequences"].size() == 4);
  // The twins' mean is the one without the real scene: (1 + 2 + 3) / 3, not (1+2+3+100) / 4.
  CHECK(sg["mean"]["cd"].get<double>() == Approx(2.0));
  CHECK(sg["mean"]["ate_m"].get<double>() == Approx(0.02));
  CHECK(sg["diff_vs_paper"]["cd"]["ours"].get<double>() == Approx(2.0));
  CHECK(sg["mean_real"]["cd"].get<double>() == Approx(100.0));
  CHECK(sg["mean_real"]["depth_rmse"].get<double>() == Approx(1000.0));
  // The harness config (and its hash) does not depend on the real root or on the scene's
  // presence: the twins' numbers can be compared tightly with a run that lacked it.
  const std::string other = test::temp_dir("harness-real-missing-2");
  std::vector<std::string> p2;
  const Json missing = harness::run_table(nuscenes_quick(other), real_seq_hooks(&p2),
                                          test::fake_context());
  CHECK_FALSE(r["config"].contains("real_root"));
  CHECK(r["config_hash"] == missing["config_hash"]);
  CHECK(r["rows"][2]["mean"] == missing["rows"][2]["mean"]);
  // compare: the run without the scene lost a sequence of the baseline, and says why.
  const auto rep = harness::compare_results(missing, r);
  CHECK(rep.regression());
  CHECK(harness::format_report(rep).find("skipped: real data not found") != std::string::npos);
  CHECK_FALSE(harness::compare_results(r, r).regression());
  // Markdown: the main table holds the twins' mean; the real scene has its own table.
  const std::string md = harness::render_markdown(r);
  const size_t real_at = md.find("## Real data: nuscenes-real-0916 (not in the means above)");
  REQUIRE(real_at != std::string::npos);
  const size_t twins_row = md.find("| SG-NLF | 2.0000 |");
  const size_t real_row = md.find("| SG-NLF | 100.0000 |");
  CHECK(twins_row < real_at);
  CHECK((real_row != std::string::npos && real_row > real_at));
  CHECK(md.find("## Sequence nuscenes-real-0916 — real data") != std::string::npos);
  // Naive baselines: the twins' (1.5 + 2.5 + 3.5) / 3 above, the scene's 100.5 in its table.
  const size_t naive_twins = md.find("| *naive baseline (nearest training scan)* | 2.5000 |");
  const size_t naive_real = md.find("| *naive baseline (nearest training scan)* | 100.5000 |");
  CHECK(naive_twins < real_at);
  CHECK((naive_real != std::string::npos && naive_real > real_at));
}

TEST_CASE("run_table: a real sequence whose folder does not load is skipped, the twins finish",
          "[harness]") {
  const std::string root = test::temp_dir("harness-real-broken");
  std::filesystem::create_directories(root + "/nuscenes-mini-scene-0916");
  std::vector<std::string> prepares;
  harness::BenchHooks h = real_seq_hooks(&prepares);
  const auto ok_prepare = h.prepare;
  h.prepare = [ok_prepare](const harness::SequenceDef& s, const harness::BenchOptions& o,
                           const std::string& dir) {
    if (s.is_real_dir()) throw IoError("fake: no scene.json");
    return ok_prepare(s, o, dir);
  };
  const Json r = harness::run_table(nuscenes_quick(root), h, test::fake_context());
  REQUIRE(r["skipped_sequences"].size() == 1);
  CHECK(r["skipped_sequences"][0]["reason"].get<std::string>().find(
            "could not be loaded: fake: no scene.json") != std::string::npos);
  CHECK(r["sequences"].size() == 3);
  const Json& sg = r["rows"][2];
  CHECK(sg["status"] == "ok");
  CHECK(sg["sequences"].size() == 3);
  CHECK(sg["mean"]["cd"].get<double>() == Approx(2.0));
  CHECK_FALSE(sg.contains("mean_real"));
}

TEST_CASE("the real-data root defaults to $SGNLF_SHARED_DIR/data/real, else ../shared/data/real",
          "[harness]") {
  const char* env = std::getenv("SGNLF_SHARED_DIR");
  const std::string saved = env ? env : "";
  ::setenv("SGNLF_SHARED_DIR", "/some/shared", 1);
  CHECK(harness::default_real_root() == "/some/shared/data/real");
  harness::BenchOptions o;
  CHECK(o.resolved_real_root() == "/some/shared/data/real");
  o.real_root = "/elsewhere";
  CHECK(o.resolved_real_root() == "/elsewhere");
  ::unsetenv("SGNLF_SHARED_DIR");
  CHECK(harness::default_real_root() == "../shared/data/real");
  harness::SequenceDef s;
  s.real_dir = "scene";
  CHECK(harness::sequence_data_root(s, o) == "/elsewhere/scene");
  o.data_root = "/data";  // --data-root wins (its windows have no real_dir anyway)
  CHECK(harness::sequence_data_root(s, o) == "/data");
  s.real_dir.clear();
  o.data_root.clear();
  CHECK(harness::sequence_data_root(s, o).empty());  // a twin: simulated
  if (env) ::setenv("SGNLF_SHARED_DIR", saved.c_str(), 1);
}
