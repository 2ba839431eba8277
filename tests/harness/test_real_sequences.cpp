// A real sequence inside a synthetic scale (tables.json `real_dir`, nuscenes-low quick): skipped
// and recorded when its folder is missing or does not load, else run from its folder and
// averaged apart from the twins; the real-data root's default.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "fake_table.hpp"
#include "harness/bench_options.hpp"
#include "harness/compare.hpp"
#include "harness/markdown.hpp"
#include "harness/tables.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;

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
