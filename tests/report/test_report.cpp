// `sgnlf report`: the page of a synthetic run folder and bench folder (report_fixture.hpp),
// checked as text: every picture is a data: URI of the file's exact bytes, the curves are
// inline SVG, inserted text is escaped, nothing refers to the network, and bad input is refused
// with the path named.
#include <catch2/catch.hpp>

#include <filesystem>

#include "core/config.hpp"
#include "core/error.hpp"
#include "geometry/range_image.hpp"
#include "metrics/anatomy.hpp"
#include "metrics/anatomy_json.hpp"
#include "report/base64.hpp"
#include "report/report.hpp"
#include "report/run_folder.hpp"
#include "report_fixture.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;
namespace fs = std::filesystem;

namespace {

std::string decode_data_uri(const std::string& uri, const std::string& mime) {
  const std::string head = "data:" + mime + ";base64,";
  REQUIRE(uri.rfind(head, 0) == 0);
  return report::base64_decode(uri.substr(head.size()));
}

bool contains(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }

}  // namespace

TEST_CASE("report of a run: every picture is embedded with the file's exact bytes", "[report]") {
  const std::string dir = test::temp_dir("report_run");
  const auto pngs = test::write_run_fixture(dir);
  const std::string html = report::build_report(dir);
  const auto srcs = test::img_sources(html);
  // top view, latest pose graph, the two renders in frame order
  REQUIRE(srcs.size() == 4);
  for (const auto& s : srcs) CHECK(s.rfind("data:", 0) == 0);
  CHECK(decode_data_uri(srcs[0], "image/svg+xml") == test::file_contents(dir + "/trajectories/top_view.svg"));
  CHECK(decode_data_uri(srcs[1], "image/svg+xml") == test::file_contents(dir + "/pose_graph/epoch_00010.svg"));
  CHECK(decode_data_uri(srcs[2], "image/png") == test::file_contents(pngs[0]));
  CHECK(decode_data_uri(srcs[3], "image/png") == test::file_contents(pngs[1]));
  CHECK(test::file_contents(pngs[0]).substr(1, 3) == "PNG");
  CHECK(contains(html, "frame 3 (3.png): depth PSNR"));
  CHECK(test::count_of(html, "class=\"tag top\">rendered<") == 2);
}

TEST_CASE("report of a run: curves, metrics and context", "[report]") {
  const std::string dir = test::temp_dir("report_run_text");
  test::write_run_fixture(dir);
  const std::string html = report::build_report(dir);
  // Loss, learning rate and ATE charts, each with drawn series.
  CHECK(test::count_of(html, "<svg class=\"chart\"") == 3);
  CHECK(test::count_of(html, "<polyline class=\"series\"") >= 4);  // total, depth, lr, 2 × ATE
  CHECK(contains(html, "<title>Learning rate</title>"));
  CHECK(contains(html, "ATE after geometric step"));
  CHECK(contains(html, "4 entries of train_log.jsonl, 2 of geometric_log.jsonl"));
  CHECK_FALSE(contains(html, "no data"));
  // Means: model vs naive (depth PSNR 27/1.05 = 25.71 vs 13.50), per frame, poses.
  CHECK(contains(html, "<span class=\"better\">25.71</span>"));
  CHECK(contains(html, "<td>13.50</td>"));
  CHECK(contains(html, "naive 13.50"));
  CHECK(contains(html, "<span class=\"better\">0.0817</span>"));
  CHECK(contains(html, "<td>3.2526</td>"));
  CHECK(contains(html, "pose_graph/epoch_00010.svg (latest of 2)"));
  CHECK(contains(html, "3 edges, 2 kept, of which 1 non-sequential"));
  CHECK(contains(html, "<td>0123456789abcdef</td>"));
  CHECK(contains(html, "<td>[0] Test Platform / test-device (CPU)</td>"));  // run.json's is empty
  CHECK(contains(html, "<td>100</td>"));                                      // step
  CHECK(contains(html, "resolved config (run.json)"));
}

TEST_CASE("report of a reconstruct folder: its poses scored by reference poses, or said not to be",
          "[report]") {
  const std::string dir = test::temp_dir("report_reconstruct");
  test::write_run_fixture(dir);
  // A plain folder's run: no pose metrics in metrics.json or summary.json.
  for (const char* name : {"/metrics.json", "/summary.json"}) {
    Json j = load_json_file(dir + name);
    j.erase("pose_metrics");
    j.erase("initial_pose_metrics");
    write_json_file(dir + name, j);
  }
  Json record{{"request", {{"scans", "/scans"}}}, {"stages", Json::object()}};
  write_json_file(dir + "/reconstruct.json", record);
  std::string html = report::build_report(dir);
  CHECK(contains(html, "No reference poses, so no ATE"));
  CHECK_FALSE(contains(html, "odometry poses"));

  record["pose_errors"] = {
      {"odometry", {{"ate_m", 0.2325}, {"rpe_t_cm", 7.48}, {"rpe_r_deg", 0.240}}},
      {"optimised", {{"ate_m", 0.2239}, {"rpe_t_cm", 7.14}, {"rpe_r_deg", 0.207}}}};
  write_json_file(dir + "/reconstruct.json", record);
  html = report::build_report(dir);
  CHECK_FALSE(contains(html, "No reference poses"));
  CHECK(contains(html, "<th>odometry poses</th>"));
  CHECK(contains(html, "<td>0.2325</td>"));
  CHECK(contains(html, "<span class=\"better\">0.2239</span>"));
}

TEST_CASE("report: the horizontal ATE beside the 3D one, and the one the reference supports",
          "[report][ate_h]") {
  const std::string dir = test::temp_dir("report_ate_h");
  test::write_run_fixture(dir);
  // A metrics.json from before ate_h_m: its row is there, blank; nothing is said to be supported.
  std::string html = report::build_report(dir);
  CHECK(contains(html, "<td>ATE horizontal (m) ↓</td><td>—</td><td><span>—</span></td>"));
  CHECK_FALSE(contains(html, "the one the reference supports"));
  // Planar reference poses (nuScenes' ego poses): the horizontal ATE is the one.
  Json m = load_json_file(dir + "/metrics.json");
  m["pose_metrics"]["ate_h_m"] = 0.0421;
  m["pose_metrics"]["ate_reference"] = "horizontal";
  m["initial_pose_metrics"]["ate_h_m"] = 2.8;
  m["initial_pose_metrics"]["ate_reference"] = "horizontal";
  write_json_file(dir + "/metrics.json", m);
  html = report::build_report(dir);
  CHECK(contains(html, "<td>ATE horizontal (m) ↓<br><small>the one the reference supports</small></td>"
                       "<td>2.8000</td><td><span class=\"better\">0.0421</span></td>"));
  CHECK(contains(html, "<td>ATE (m) ↓</td>"));
  CHECK(contains(html, "The reference poses are planar"));
  // A reference that varies in z supports the 3D ATE.
  m["pose_metrics"]["ate_reference"] = "3d";
  write_json_file(dir + "/metrics.json", m);
  html = report::build_report(dir);
  CHECK(contains(html, "<td>ATE (m) ↓<br><small>the one the reference supports</small></td>"));
  CHECK(contains(html, "<td>ATE horizontal (m) ↓</td>"));
  CHECK(contains(html, "they support the 3D ATE"));
  CHECK_FALSE(contains(html, "The reference poses are planar"));
}

TEST_CASE("report: inserted text is escaped and nothing refers to the network", "[report]") {
  const std::string dir = test::temp_dir("report_escape");
  test::write_run_fixture(dir);
  const std::string html = report::build_report(dir);
  CHECK(contains(html, "seq &lt;b&gt;&amp;&quot;x&#39;"));
  CHECK_FALSE(contains(html, "<b>"));
  CHECK_FALSE(contains(html, "<tag>"));
  CHECK(contains(html, "a &lt;tag&gt; &amp; more"));  // inside the config block
  CHECK_FALSE(contains(html, "http://"));
  CHECK_FALSE(contains(html, "https://"));
  CHECK_FALSE(contains(html, "<link"));
  CHECK_FALSE(contains(html, "<script src"));
  CHECK(test::count_of(html, "<script>") == 1);  // the picture check, inline
}

TEST_CASE("report: the top view is drawn from the TUM files; missing renders are said", "[report]") {
  const std::string dir = test::temp_dir("report_drawn");
  test::write_run_fixture(dir, {false, false});
  const std::string html = report::build_report(dir);
  CHECK(test::count_of(html, "<svg class=\"chart\"") == 4);
  CHECK(contains(html, "<title>Trajectories from above (TUM files; metres, not aligned)</title>"));
  CHECK(contains(html, "No renders (no renders/ folder in the run; give --renders DIR)"));
  CHECK(test::img_sources(html).size() == 1);  // the pose graph only
  // --renders elsewhere: those pictures, and only up to max_images of them.
  const std::string other = test::temp_dir("report_renders_src");
  const auto pngs = test::write_run_fixture(other);
  const std::string two = report::build_report(dir, {other + "/renders", 24});
  CHECK(test::img_sources(two).size() == 3);
  const std::string one = report::build_report(dir, {other + "/renders", 1});
  REQUIRE(test::img_sources(one).size() == 2);
  CHECK(decode_data_uri(test::img_sources(one)[1], "image/png") == test::file_contents(pngs[0]));
  CHECK(contains(one, "1 more pictures not embedded"));
}

TEST_CASE("report of a run with anatomy.json: the shares beside the nearest scan's, its pictures",
          "[report][anatomy]") {
  const std::string dir = test::temp_dir("report_anatomy");
  test::write_run_fixture(dir);
  // Without anatomy.json the page has no anatomy section.
  CHECK_FALSE(contains(report::build_report(dir), "Error anatomy"));
  // One view: ours with a false return at 30 m (all of its depth error), the nearest scan's
  // with a missed return (all of its).
  Sensor s = sensor_preset("kitti360");
  s.height = 4;
  s.width = 16;
  RangeImage gt(s.height, s.width);
  for (size_t i = 1; i < gt.size(); ++i) gt.range[i] = 12.f, gt.ray_drop[i] = 1.f;
  RangeImage ours = gt, nearest = gt;
  for (size_t i = 0; i < gt.size(); ++i) ours.ray_drop[i] = nearest.ray_drop[i] = gt.ray_drop[i];
  ours.range[0] = 30.f, ours.ray_drop[0] = 1.f;
  nearest.ray_drop[5] = 0.f;
  const Json ja = metrics::anatomy_json(metrics::view_anatomy(s, ours, gt));
  const Json jn = metrics::anatomy_json(metrics::view_anatomy(s, nearest, gt));
  Json fa = ja, fn = jn;
  fa["frame"] = fn["frame"] = 3;
  write_json_file(dir + "/anatomy.json",
                  Json{{"model", {{"mean", ja}, {"per_frame", {fa}}}},
                       {"naive_baseline", {{"mean", jn}, {"per_frame", {fn}}}}});
  io::RgbImage pic;
  pic.height = 2, pic.width = 3, pic.rgb.assign(18, 200);
  io::write_png(dir + "/anatomy/3.png", pic);
  const std::string html = report::build_report(dir);
  REQUIRE(contains(html, "<h2>Error anatomy</h2>"));
  const std::string section = html.substr(html.find("<h2>Error anatomy</h2>"));
  // Columns: CD pred→GT, CD GT→pred, depth MSE, each ours then the nearest scan's. Ours: all
  // of pred→GT and of the depth MSE is the false return, GT→pred is 0 (its share undefined);
  // the nearest scan's: all of GT→pred and of the depth MSE is the missed return; a cause a
  // direction does not have is "—".
  CHECK(contains(section, "<td>cause</td><td>false</td><td>100.0 %</td><td>—</td><td>—</td><td>—</td><td>100.0 %</td><td>0.0 %</td>"));
  CHECK(contains(section, "<td>cause</td><td>missed</td><td>—</td><td>—</td><td>—</td><td>100.0 %</td><td>0.0 %</td><td>100.0 %</td>"));
  CHECK(contains(section, "<td>range</td><td>20-40m</td><td>100.0 %</td>"));
  CHECK(contains(section, "frame 3: ours, the nearest scan, the observed scan"));
  const auto srcs = test::img_sources(section);
  REQUIRE_FALSE(srcs.empty());
  CHECK(decode_data_uri(srcs[0], "image/png") == test::file_contents(dir + "/anatomy/3.png"));
}

TEST_CASE("report: write_report writes <dir>/report.html or --out", "[report]") {
  const std::string dir = test::temp_dir("report_write");
  test::write_run_fixture(dir);
  CHECK(report::write_report(dir) == dir + "/report.html");
  CHECK(test::file_contents(dir + "/report.html") == report::build_report(dir));
  const std::string out = test::temp_dir("report_write_out") + "/page.html";
  CHECK(report::write_report(dir, out) == out);
  CHECK(fs::file_size(out) > 1000);
}

TEST_CASE("report of a bench folder: the table, one section per run, links to them", "[report]") {
  const std::string dir = test::temp_dir("report_bench");
  const std::string run = dir + "/runs/sg-nlf/seq-a";
  test::write_run_fixture(run);
  Json seq = {{"sequence", "seq-a"}, {"metrics", test::metric_block(1.0)},
              {"pose_metrics", {{"ate_m", 0.0817}}},
              {"extra", {{"naive_baseline", test::metric_block(2.0)}}}};
  write_json_file(dir + "/results.json",
                  Json{{"title", "A <table>"}, {"table", "t"}, {"scale", "smoke"},
                       {"columns", {"cd", "depth_psnr"}}, {"extra_columns", {"ate_m"}},
                       {"sequences", {{{"name", "seq-a"}}}},
                       {"rows", {{{"method", "sg-nlf"}, {"label", "SG-NLF & co"}, {"status", "ok"},
                                  {"mean", test::metric_block(1.0)},
                                  {"paper", {{"cd", 0.1695}}}, {"sequences", {seq}}},
                                 {{"method", "geonlf"}, {"label", "GeoNLF"}, {"status", "skipped"},
                                  {"sequences", Json::array()}}}}});
  const std::string html = report::build_report(dir);
  CHECK(contains(html, "<title>sgnlf report: A &lt;table&gt;</title>"));
  CHECK(contains(html, "SG-NLF &amp; co"));
  CHECK(contains(html, "paper 0.1695"));
  CHECK(contains(html, "not run (--rows)"));
  CHECK(contains(html, "<em>naive baseline</em>"));
  CHECK(contains(html, "<td>13.50</td>"));  // the naive baseline's depth PSNR
  CHECK(contains(html, "<a href=\"#run-sg-nlf-seq-a\">"));
  CHECK(test::count_of(html, "<article id=\"run-sg-nlf-seq-a\">") == 1);
  CHECK(test::img_sources(html).size() == 4);  // the run's pictures
  CHECK_FALSE(contains(html, "http://"));
  CHECK_THROWS_AS(report::build_report(dir, {run + "/renders", 24}), ConfigError);
}

TEST_CASE("report refuses what is not a run or bench folder, naming the path", "[report]") {
  const std::string base = test::temp_dir("report_refuse");
  auto message = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const IoError& e) {
      return std::string(e.what());
    }
    return std::string("no IoError");
  };
  const std::string missing = base + "/does-not-exist";
  CHECK(contains(message([&] { report::build_report(missing); }), missing + ": no such folder"));
  CHECK(contains(message([&] { report::build_report(base); }),
                 base + ": neither a run folder (no run.json) nor a bench folder (no results.json)"));
  CHECK(contains(message([&] { report::load_run_folder(base); }), base));
  // A damaged log line (not the last, unterminated one) names the file and line.
  const std::string run = base + "/run";
  test::write_run_fixture(run);
  test::write_text(run + "/train_log.jsonl", "{\"step\": 1}\nnot json\n{\"step\": 2}\n");
  CHECK(contains(message([&] { report::build_report(run); }), run + "/train_log.jsonl:2"));
  CHECK(contains(message([&] { report::build_report(run, {base + "/nope", 24}); }), base + "/nope"));
}

TEST_CASE("read_json_lines skips only an unterminated last line", "[report]") {
  const std::string dir = test::temp_dir("report_jsonl");
  test::write_text(dir + "/a.jsonl", "{\"a\":1}\n\n{\"a\":2}\n{\"a\":");
  const auto v = report::read_json_lines(dir + "/a.jsonl");
  REQUIRE(v.size() == 2);
  CHECK(v[1]["a"] == 2);
  CHECK(report::read_json_lines(dir + "/missing.jsonl").empty());
  test::write_text(dir + "/b.jsonl", "{\"a\":1}\n{\"a\":\n");
  CHECK_THROWS_AS(report::read_json_lines(dir + "/b.jsonl"), IoError);
}
