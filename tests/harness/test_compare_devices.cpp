// sgnlf compare across devices and machines: a smoke table is tight on its baseline's device,
// against its own device's baseline (harness/device_baseline.hpp: the slug, the path beside the
// committed baseline, the choice) or while another device computes the same numbers, else loose
// with a note naming both devices and where that device's baseline goes; loose still fails a
// metric beyond the loose tolerance, a non-finite metric, a missing row and other configs. A
// committed quick-table cell rerun on another CPU passes with another training outcome, within
// the cell's seed spread, and fails when regressed. The rest of compare: test_compare.cpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "fake_table.hpp"
#include "harness/compare.hpp"
#include "harness/device_baseline.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;
using harness::compare_results;

namespace {
bool has_finding(const harness::CompareReport& rep, const std::string& kind, bool fails,
                 const std::vector<std::string>& words) {
  for (const auto& f : rep.findings) {
    if (f.kind != kind || f.fails != fails) continue;
    bool all = true;
    for (const auto& w : words) all = all && f.message.find(w) != std::string::npos;
    if (all) return true;
  }
  return false;
}
}  // namespace

TEST_CASE("a committed cell rerun on another CPU: another outcome passes, regressed fails",
          "[harness][compare]") {
  // The main command's situation (scripts/run.sh): SG-NLF on kitti360-low-a rerun on another
  // machine and compared, as a subset, with the committed table, whose cell holds seeds 1 and 2
  // (mean ± sd). The other run here is a real one: the committed seed-2 run, a different
  // training outcome with every metric the evaluation writes today, presented as a seed-1 run
  // of another CPU. It takes seed 1's config hash: while a row is being rerun with a new preset
  // its two seeds may carry different hashes, and what is tested here is the metrics' spread.
  const std::string root = test::source_dir() + "/results/";
  const Json table = load_json_file(root + "tables/kitti360-low/quick/results.json");
  const auto cell_of = [](const Json& r) {
    for (const auto& row : r["rows"])
      if (row["method"] == "sg-nlf")
        for (const auto& s : row["sequences"])
          if (s["sequence"] == "kitti360-low-a") return s;
    FAIL("no sg-nlf / kitti360-low-a cell");
    return Json();
  };
  const Json committed = cell_of(table);
  REQUIRE(committed["seeds"] == Json::array({1, 2}));
  Json fresh = table;  // a subset result: one row, one sequence, seed 1, another CPU
  fresh["config"].erase("seeds");
  fresh["config"]["seed"] = 1;
  fresh["config_hash"] = "0000000000000000";  // a `bench --rows --sequences` run's own
  fresh["context"]["opencl"]["device"] = "pthread-znver4-AMD EPYC 9B14";
  fresh["context"]["machine"]["cpu_id"] = "AuthenticAMD family 25 model 17 stepping 1";
  Json other = committed["runs"][1];
  REQUIRE(other["seed"] == 2);
  other.erase("source");
  other["seed"] = 1;
  other["config_hash"] = committed["runs"][0]["config_hash"];
  Json rows = Json::array();
  for (auto row : table["rows"]) {
    if (row["method"] != "sg-nlf") continue;
    row["sequences"] = Json::array({other});
    row["mean"] = other["metrics"];
    for (const char* k : {"mean_sd", "mean_by_seed", "mean_real", "mean_real_sd", "mean_real_by_seed"})
      row.erase(k);
    rows.push_back(row);
  }
  fresh["rows"] = rows;
  harness::CompareOptions opt;
  opt.subset = true;
  opt.timings = false;
  const auto improved = compare_results(fresh, table, opt);
  INFO(harness::format_report(improved));
  CHECK(improved.mode == "loose");
  CHECK_FALSE(improved.regression());
  CHECK(improved.metrics_compared >= 40);  // the median_/mix_ variants and parts were compared
  CHECK(improved.seed_spread_used >= 40);  // the one run against the cell's two seeds' spread
  // Regressed: CD and its parts 3 x (beyond the loose 1.4 x), F-score 0.15 lower, each also
  // 4 seed sd beyond the cell's mean, so that two seeds far apart do not absorb it.
  Json worse = fresh;
  Json& m = worse["rows"][0]["sequences"][0]["metrics"];
  const auto sd = [&](const char* k) { return committed["metrics_sd"][k].get<double>(); };
  for (const char* k : {"cd", "cd_pred_to_gt", "cd_gt_to_pred", "median_cd", "mix_cd"})
    m[k] = committed["metrics"][k].get<double>() * 3.0 + 4.0 * sd(k);
  m["fscore"] = committed["metrics"]["fscore"].get<double>() - 0.15 - 4.0 * sd("fscore");
  const auto regressed = compare_results(worse, table, opt);
  INFO(harness::format_report(regressed));
  CHECK(regressed.regression());
  int cd_fails = 0, other_fails = 0;
  for (const auto& f : regressed.findings) {
    if (!f.fails) continue;
    const bool cd_like = f.where.find("/ cd") != std::string::npos ||
                         f.where.find("_cd") != std::string::npos ||
                         f.where.find("/ fscore") != std::string::npos;
    (cd_like ? cd_fails : other_fails) += 1;
    CHECK(f.kind == "regression");
  }
  CHECK(cd_fails == 6);
  CHECK(other_fails == 0);
}

TEST_CASE("a smoke table is tight on its baseline's device, loose on another without its own",
          "[harness][compare]") {
  const Json base = test::fake_results();
  REQUIRE(base["scale"] == "smoke");
  const double cd = base["rows"][0]["mean"]["cd"].get<double>();
  Json drift = base;  // 1 % worse: beyond the tight tolerances, well within the loose ones
  test::row(drift, "lidar-nerf")["mean"]["cd"] = cd * 1.01;
  // The baseline's own device: a deterministic twin, so tight, and the drift fails.
  auto rep = compare_results(drift, base);
  CHECK(rep.mode == "tight");
  CHECK(rep.regression());
  // Another device, no baseline of that device: its rounding, amplified by 60 training steps,
  // moves an untrained model's metrics, so loose; the report says the device differs, that no
  // baseline of it exists, where to put one, and which metrics missed the tight tolerances.
  Json other = drift;
  other["context"]["opencl"]["device"] = "another-device";
  harness::CompareOptions opt;
  opt.device_baseline = "tables/t/smoke/devices/another-device_1.0/results.json";
  rep = compare_results(other, base, opt);
  CHECK(rep.mode == "loose");
  CHECK_FALSE(rep.regression());
  CHECK(has_finding(rep, "note", false,
                    {"the device differs", "another-device", "fake-device",
                     "no baseline of this device exists",
                     "copy this run's results.json to " + opt.device_baseline}));
  CHECK(has_finding(rep, "note", false, {"not the tight ones", "lidar-nerf / mean / cd"}));
  CHECK_THAT(harness::format_report(rep), Catch::Contains("loose tolerances (smoke scale on another"));
  // ... the same for another driver or another device profile on the same device.
  Json driver = drift;
  driver["context"]["opencl"]["driver_version"] = "2.0";
  CHECK(compare_results(driver, base).mode == "loose");
  CHECK_FALSE(compare_results(driver, base).regression());
  Json profiled_base = base, profile = drift;
  profiled_base["context"]["device_profile"] = {{"name", "cpu"}};
  profile["context"]["device_profile"] = {{"name", "gpu"}};
  CHECK(compare_results(profile, profiled_base).mode == "loose");
  CHECK_FALSE(compare_results(profile, profiled_base).regression());
  // Loose still fails on what is not rounding: a metric beyond the loose tolerance, a non-finite
  // metric, a missing row, other configs.
  Json gross = other;
  test::row(gross, "lidar-nerf")["mean"]["cd"] = cd * 3;
  CHECK(compare_results(gross, base).regression());
  Json nan = other;
  test::row(nan, "lidar-nerf")["sequences"][0]["metrics"]["depth_psnr"] = std::nan("");
  rep = compare_results(nan, base);
  CHECK(rep.regression());
  CHECK(has_finding(rep, "regression", true, {"not finite"}));
  Json missing = other;
  missing["rows"].erase(0);
  CHECK(compare_results(missing, base).regression());
  Json cfg = other;
  test::row(cfg, "lidar-nerf")["sequences"][0]["config_hash"] = "ffffffffffffffff";
  rep = compare_results(cfg, base);
  CHECK(rep.regression());
  CHECK_THAT(harness::format_report(rep), Catch::Contains("lidar-nerf / ") && Catch::Contains("ffffffffffffffff"));
  // Another device that computes the same numbers (another PoCL CPU target) is still a twin:
  // tight, and a note names both devices. (CI moved from a skylake-avx512 to a haswell PoCL
  // target and every one of 400 metrics matched.)
  Json same_numbers = base;
  same_numbers["context"]["opencl"]["device"] = "another-device";
  rep = compare_results(same_numbers, base, {"auto", true});
  CHECK(rep.mode == "tight");
  CHECK_FALSE(rep.regression());
  CHECK_THAT(harness::format_report(rep), Catch::Contains("another-device") &&
                                               Catch::Contains("every metric still matches"));
  // Same device, another run config: not a twin either, and the message says which.
  test::row(cfg, "lidar-nerf")["mean"]["cd"] = cd;
  cfg["context"]["opencl"]["device"] = base["context"]["opencl"]["device"];
  rep = compare_results(cfg, base);
  CHECK(rep.regression());
  CHECK(has_finding(rep, "not-twins", true, {"ffffffffffffffff"}));
  // An explicit mode is the user's choice: tight fails the other device's drift, loose passes
  // the same device's.
  CHECK(compare_results(other, base, {"tight"}).regression());
  CHECK_FALSE(compare_results(drift, base, {"loose"}).regression());
}

TEST_CASE("a smoke result from another device is compared with that device's own baseline",
          "[harness][compare]") {
  const Json base = test::fake_results();
  const std::string dir = test::temp_dir("compare_device_baseline");
  const std::string committed = dir + "/smoke/results.json";
  std::filesystem::create_directories(dir + "/smoke");
  write_text_file(committed, base.dump());
  // The GPU's own smoke run: another device and profile, and numbers 5 % off the committed ones
  // (its rounding over 60 steps), copied beside the committed baseline.
  Json gpu = base;
  gpu["context"]["opencl"]["device"] = "NVIDIA H100 80GB HBM3";
  gpu["context"]["opencl"]["driver_version"] = "550.54.15";
  gpu["context"]["device_profile"] = {{"name", "gpu"}};
  const double cd = base["rows"][0]["mean"]["cd"].get<double>();
  test::row(gpu, "lidar-nerf")["mean"]["cd"] = cd * 1.05;
  CHECK(harness::device_slug(gpu) == "nvidia-h100-80gb-hbm3_550.54.15_gpu");
  const std::string own = harness::device_baseline_path(committed, gpu);
  CHECK(own == dir + "/smoke/devices/nvidia-h100-80gb-hbm3_550.54.15_gpu/results.json");
  // Before it exists: looked for, not found; the comparison is loose and names the path.
  Json gpu_drift = gpu;
  test::row(gpu_drift, "lidar-nerf")["mean"]["cd"] = cd * 1.05 * 1.01;
  auto choice = harness::choose_baseline(committed, base, gpu_drift);
  CHECK_FALSE(choice.per_device);
  CHECK(choice.path == committed);
  CHECK(choice.looked_for == own);
  harness::CompareOptions opt;
  opt.device_baseline = choice.looked_for;
  auto rep = compare_results(gpu_drift, choice.baseline, opt);
  CHECK(rep.mode == "loose");
  CHECK_FALSE(rep.regression());
  CHECK(has_finding(rep, "note", false, {"no baseline of this device exists", own}));
  // With it: the GPU's results are compared tightly with the GPU's own numbers. Its own rerun
  // passes; the 1 % drift that passed loosely above now fails.
  std::filesystem::create_directories(std::filesystem::path(own).parent_path());
  write_text_file(own, gpu.dump());
  choice = harness::choose_baseline(committed, base, gpu);
  REQUIRE(choice.per_device);
  CHECK(choice.path == own);
  CHECK(choice.baseline == gpu);
  opt.device_baseline = choice.looked_for;
  opt.device_baseline_used = true;
  rep = compare_results(gpu, choice.baseline, opt);
  CHECK(rep.mode == "tight");
  CHECK_FALSE(rep.regression());
  CHECK(has_finding(rep, "note", false, {"this device's own baseline", own}));
  choice = harness::choose_baseline(committed, base, gpu_drift);
  REQUIRE(choice.per_device);
  rep = compare_results(gpu_drift, choice.baseline, opt);
  CHECK(rep.mode == "tight");
  CHECK(rep.regression());
  // The committed baseline's own device never looks for one; nor does a trained table.
  choice = harness::choose_baseline(committed, base, base);
  CHECK_FALSE(choice.per_device);
  CHECK(choice.looked_for.empty());
  Json quick = base, quick_gpu = gpu;
  quick["scale"] = quick_gpu["scale"] = "quick";
  CHECK(harness::choose_baseline(committed, quick, quick_gpu).looked_for.empty());
  // The slug of a PoCL result (this machine's), and of a result without a profile.
  Json pocl = base;
  pocl["context"]["opencl"] = {{"device", "pthread-skylake-avx512-AMD EPYC"}, {"driver_version", "3.1+debian"}};
  CHECK(harness::device_slug(pocl) == "pthread-skylake-avx512-amd-epyc_3.1-debian");
  pocl["context"]["device_profile"] = {{"name", "cpu"}};
  CHECK(harness::device_slug(pocl) == "pthread-skylake-avx512-amd-epyc_3.1-debian_cpu");
}
