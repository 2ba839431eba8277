// sgnlf compare: identical results pass; a worsened metric, a missing metric, row or sequence
// fail; improvements only fail with --strict; timing noise below the ratio or with too few
// repetitions is not flagged, a large median ratio over enough repetitions is.
#include <catch2/catch.hpp>

#include "fake_table.hpp"
#include "harness/compare.hpp"

using namespace sgnlf;
using harness::compare_results;

namespace {
Json& row(Json& r, const std::string& method) {
  for (auto& x : r["rows"])
    if (x["method"] == method) return x;
  FAIL("no row " << method);
  return r;
}
int fails(const harness::CompareReport& rep) {
  int n = 0;
  for (const auto& f : rep.findings) n += f.fails;
  return n;
}
}  // namespace

TEST_CASE("identical results pass in tight mode", "[harness][compare]") {
  const Json base = test::fake_results();
  const auto rep = compare_results(base, base);
  CHECK(rep.mode == "tight");
  CHECK_FALSE(rep.regression());
  CHECK(rep.metrics_compared > 0);
  CHECK(rep.timings_compared > 0);
}

TEST_CASE("a deliberately worsened metric fails", "[harness][compare]") {
  const Json base = test::fake_results();
  Json worse = base;
  row(worse, "lidar-nerf")["mean"]["cd"] = base["rows"][0]["mean"]["cd"].get<double>() * 1.5;
  auto rep = compare_results(worse, base);
  CHECK(rep.regression());
  CHECK(fails(rep) == 1);
  // Also in loose mode (different device), a 50 % worse Chamfer distance is out of tolerance.
  rep = compare_results(worse, base, {"loose"});
  CHECK(rep.regression());
  // A worse PSNR (higher is better) on one sequence fails too.
  Json psnr = base;
  row(psnr, "sg-nlf")["sequences"][1]["metrics"]["depth_psnr"] = 10.0;
  CHECK(compare_results(psnr, base).regression());
}

TEST_CASE("improvements beyond tolerance fail only when strict", "[harness][compare]") {
  const Json base = test::fake_results();
  Json better = base;
  row(better, "lidar-nerf")["mean"]["cd"] = 0.01;
  CHECK_FALSE(compare_results(better, base).regression());
  harness::CompareOptions strict;
  strict.strict = true;
  CHECK(compare_results(better, base, strict).regression());
}

TEST_CASE("tight and loose tolerances", "[harness][compare]") {
  const Json base = test::fake_results();
  Json drift = base;
  const double cd = base["rows"][0]["mean"]["cd"].get<double>();
  row(drift, "lidar-nerf")["mean"]["cd"] = cd * 1.01;  // 1 % worse
  CHECK(compare_results(drift, base, {"tight"}).regression());
  CHECK_FALSE(compare_results(drift, base, {"loose"}).regression());
  // auto → loose when the device differs.
  drift["context"]["opencl"]["device"] = "another-device";
  const auto rep = compare_results(drift, base);
  CHECK(rep.mode == "loose");
  CHECK_FALSE(rep.regression());
  CHECK(harness::metric_tolerance("cd", "loose", 0.1) == Approx(0.005 + 0.25 * 0.1));
}

TEST_CASE("missing metric, sequence and row are reported and fail", "[harness][compare]") {
  const Json base = test::fake_results();
  Json m = base;
  row(m, "lidar-nerf")["mean"].erase("depth_psnr");
  auto rep = compare_results(m, base);
  CHECK(rep.regression());
  bool seen = false;
  for (const auto& f : rep.findings)
    seen |= f.kind == "missing" && f.where.find("depth_psnr") != std::string::npos;
  CHECK(seen);

  Json s = base;
  row(s, "sg-nlf")["sequences"].erase(1);
  CHECK(compare_results(s, base).regression());

  Json r = base;
  r["rows"].erase(0);
  rep = compare_results(r, base);
  CHECK(rep.regression());
  CHECK(rep.findings.front().where == "lidar-nerf");

  // A row that ran in the baseline and fails now is a regression.
  const Json failed = test::fake_results(true);
  CHECK(compare_results(failed, base).regression());
  // The reverse (a row newly running) is a note, not a failure.
  CHECK_FALSE(compare_results(base, failed).regression());
}

TEST_CASE("timings: noise below the ratio is not flagged, a large ratio is", "[harness][compare]") {
  const Json base = test::fake_results();
  auto scale_steps = [&](double f, int n) {
    Json t = base;
    Json& tim = row(t, "lidar-nerf")["timings"]["step"];
    Json reps = Json::array();
    for (int i = 0; i < n; ++i) reps.push_back(f * (0.010 + 0.001 * i));
    tim = Json{{"reps", reps}};
    return t;
  };
  // Base has 12 repetitions of "step" (6 per sequence × 2 sequences).
  CHECK_FALSE(compare_results(scale_steps(1.4, 12), base).regression());
  const auto slow = compare_results(scale_steps(4.0, 12), base);
  CHECK(slow.regression());
  CHECK(slow.findings.front().kind == "timing");
  // Too few repetitions: not compared.
  CHECK_FALSE(compare_results(scale_steps(4.0, 2), base).regression());
  // Another device: timings are not compared.
  Json other = scale_steps(4.0, 12);
  other["context"]["opencl"]["device"] = "gpu";
  CHECK_FALSE(compare_results(other, base).regression());
  // --no-timings
  harness::CompareOptions no_t;
  no_t.timings = false;
  CHECK_FALSE(compare_results(scale_steps(4.0, 12), base, no_t).regression());
}

TEST_CASE("results of another schema or table are not comparable", "[harness][compare]") {
  const Json base = test::fake_results();
  Json v = base;
  v["schema_version"] = 999;
  CHECK(compare_results(v, base).regression());
  Json t = base;
  t["table"] = "nuscenes-low";
  CHECK(compare_results(t, base).regression());
  CHECK_THROWS_AS(compare_results(base, base, {"medium"}), ConfigError);
}
