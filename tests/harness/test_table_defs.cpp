// Table definitions (runtime/harness/tables.json): every table parses, its columns and paper
// numbers are consistent; nuscenes-low's real scene and kitti360-dynamic's set; the checks on
// a sequence's real_dir and test_frames.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "core/config.hpp"
#include "harness/tables.hpp"

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
