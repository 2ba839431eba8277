// Sequence preparation for `sgnlf bench`: a synthetic twin is simulated into the folder the
// pipeline reads; a real KITTI-360 window (--data-root) is copied out in the same layout with
// exactly the protocol window. The "real" tree is a simulated one with its sgnlf metadata
// removed, which is KITTI-360's raw layout. The same window read as a real sequence of a
// synthetic scale (<real_root>/<real_dir>), and nuscenes-low's real scene-0916 from
// ../shared/data/real when present, else from the in-repo sample (its first 2 keyframes).
#include <catch2/catch.hpp>

#include <filesystem>

#include "core/config.hpp"
#include "datasets/loader.hpp"
#include "harness/prepare.hpp"
#include "harness/tables.hpp"
#include "support/real_data.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;
namespace fs = std::filesystem;

TEST_CASE("prepare a synthetic smoke sequence", "[harness][data]") {
  const std::string dir = test::temp_dir("harness-prepare-syn");
  harness::SequenceDef s;
  s.name = "kitti360-1538";
  s.preset = "kitti360";
  s.frequency = "standard";
  s.frames = 14;
  s.width = 128;
  harness::BenchOptions o;
  const auto p = harness::prepare_sequence(s, o, dir + "/seq");
  CHECK(p.dataset["frames"] == 14);
  CHECK(p.dataset["sensor"]["width"] == 128);
  CHECK(p.dataset["test"] == Json::array({13}));  // protocol §3: every 13th from 13
  CHECK(p.dataset["seed"] == harness::kSyntheticDataSeed);
  const Dataset d = load_dataset(p.dataset_dir);
  CHECK(d.frames.size() == 14);
  CHECK(d.source == "synthetic");
}

TEST_CASE("prepare a real KITTI-360 window", "[harness][data]") {
  const std::string root = test::temp_dir("harness-prepare-real");
  // A KITTI-360-like tree: simulate 20 frames, then drop the synthetic metadata.
  harness::SequenceDef sim;
  sim.name = "kitti360-1728";
  sim.preset = "kitti360";
  sim.frequency = "standard";
  sim.frames = 20;
  sim.width = 128;
  harness::prepare_sequence(sim, harness::BenchOptions{}, root + "/kitti360");
  fs::remove(root + "/kitti360/sgnlf_dataset.json");
  fs::remove(root + "/kitti360/sensor.json");

  harness::SequenceDef win;
  win.name = "window";
  win.preset = "kitti360";
  win.frequency = "low";
  win.sequence = "kitti360-1728_sync";
  win.start = 2;
  win.frames = 4;
  win.stride = 5;
  harness::BenchOptions o;
  o.data_root = root + "/kitti360";
  const auto p = harness::prepare_sequence(win, o, root + "/prepared");
  CHECK(p.dataset["frame_ids"] == Json::array({2, 7, 12, 17}));
  CHECK(p.dataset["frequency"] == "low");
  CHECK(p.dataset["seed"].is_null());
  const Dataset d = load_dataset(p.dataset_dir);
  REQUIRE(d.frames.size() == 4);
  CHECK(d.frames[1].id == 7);
  CHECK(d.sensor.width == 1030);  // the real layout's sensor (KITTI-360 preset)

  // The same window as a real sequence of a synthetic scale: no --data-root, the folder is
  // <real_root>/<real_dir>.
  harness::SequenceDef rd = win;
  rd.real_dir = "kitti360";
  harness::BenchOptions ro;
  ro.real_root = root;
  const auto q = harness::prepare_sequence(rd, ro, root + "/prepared-real-dir");
  CHECK(q.dataset["frame_ids"] == Json::array({2, 7, 12, 17}));
  CHECK(q.dataset["seed"].is_null());
  CHECK(q.dataset["generator"]["real_path"] == root + "/kitti360");
  CHECK(load_dataset(q.dataset_dir).sensor.width == 1030);
}

TEST_CASE("prepare a dynamic twin: LiDAR4D's split, and a table's own test frames", "[harness][data]") {
  const std::string dir = test::temp_dir("harness-prepare-dyn");
  harness::SequenceDef s = harness::table_sequences(harness::table_def("kitti360-dynamic"), "smoke", false)[0];
  s.width = 96;
  const auto p = harness::prepare_sequence(s, harness::BenchOptions{}, dir + "/seq");
  CHECK(p.dataset["frames"] == 16);
  CHECK(p.dataset["test"] == Json::array({10}));  // every 10th strictly inside the window
  const Dataset d = load_dataset(p.dataset_dir);
  CHECK(d.split.test == std::vector<int>{10});
  CHECK(d.frames[0].labels.size() == d.frames[0].points.size());
  CHECK_FALSE(d.frames[0].actors.empty());
  // A table's test_frames replace it (as for the real windows of LiDAR4D's set).
  s.test_frames = {3, 9};
  const auto q = harness::prepare_sequence(s, harness::BenchOptions{}, dir + "/seq2");
  CHECK(q.dataset["test"] == Json::array({3, 9}));
  s.test_frames = {16};
  CHECK_THROWS_WITH(harness::prepare_sequence(s, harness::BenchOptions{}, dir + "/seq3"),
                    Catch::Contains("test frame position 16"));
}

TEST_CASE("prepare the nuscenes-low table's real scene from the real-data root",
          "[harness][data][real]") {
  const auto seqs = harness::table_sequences(harness::table_def("nuscenes-low"), "quick", false);
  const harness::SequenceDef& s = seqs.back();
  REQUIRE(s.is_real_dir());
  const test::RealData r = test::real_data(s.real_dir);
  if (!r) return;
  const std::string real_root = r.full ? test::real_data_root() : test::real_sample_root();
  harness::BenchOptions o;
  o.real_root = real_root;
  const std::string dir = test::temp_dir("harness-prepare-nuscenes-real");
  const auto p = harness::prepare_sequence(s, o, dir + "/seq");
  // The protocol window: the first 36 of scene-0916's 2 Hz keyframes, test views 4, 12, 20
  // (the sample: its 2 keyframes, no test view).
  const int n = r.full ? 36 : 2;
  CHECK(p.dataset["frames"] == n);
  Json ids = Json::array();
  for (int i = 0; i < n; ++i) ids.push_back(i);  // keyframe positions in the scene
  CHECK(p.dataset["frame_ids"] == ids);
  CHECK(p.dataset["frequency"] == "low");
  CHECK(p.dataset["test"] == (r.full ? Json::array({4, 12, 20}) : Json::array()));
  CHECK(p.dataset["seed"].is_null());
  CHECK(p.dataset["generator"]["real_source"] == "nuscenes");
  CHECK(p.dataset["generator"]["real_path"] == real_root + "/" + s.real_dir);
  const Dataset d = load_dataset(p.dataset_dir);
  REQUIRE(d.frames.size() == size_t(n));
  CHECK_FALSE(d.frames[0].points.empty());
  CHECK(d.planar_reference);  // the copy keeps nuScenes' planar reference (horizontal ATE)
}
