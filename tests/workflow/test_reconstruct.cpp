// sgnlf reconstruct on a folder of the tiny scene's scans written as PCD files named by their
// microsecond timestamps (no poses, a given sensor file): every stage runs and leaves its
// files; the training starts exactly at the odometry; nothing scores poses without a
// reference; a rerun skips every stage, a rerun after a kill past the training resumes from
// the evaluation without training again, a rerun with reference poses adds ATE/RPE; another
// request on the folder, a method that does not recover poses, and the poses-needing starts on
// scans without poses are refused. And `sgnlf reconstruct` killed with SIGKILL during the
// training, run again, ends equal to the uninterrupted job.
#include <catch2/catch.hpp>

#include <signal.h>

#include <cstdio>
#include <filesystem>

#include "core/config.hpp"
#include "core/error.hpp"
#include "datasets/loader.hpp"
#include "geometry/sensor.hpp"
#include "io/cloud_writers.hpp"
#include "io/pcd_reader.hpp"
#include "io/trajectory_io.hpp"
#include "pipeline/train/checkpoint.hpp"
#include "pipeline/train/trainer.hpp"
#include "pipeline/train/pose_init.hpp"
#include "support/files.hpp"
#include "support/spawn.hpp"
#include "support/test_device.hpp"
#include "workflow/reconstruct.hpp"
#include "../pipeline/tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
namespace fs = std::filesystem;

namespace {

struct ScanFolder {
  std::string dir, sensor, reference, config;
  size_t points = 0;
};

// The tiny scene's scans as scans/<16-digit μs>.pcd (10 Hz), its sensor as sensor.json, its
// poses as reference.kitti.txt, and the SG-NLF smoke preset shrunk as config.json.
ScanFolder write_scan_folder(const fs::path& root) {
  const Dataset& d = test::tiny_dataset();
  ScanFolder s;
  s.dir = (root / "scans").string();
  fs::create_directories(s.dir);
  for (size_t k = 0; k < d.frames.size(); ++k) {
    char name[64];
    std::snprintf(name, sizeof name, "lidar_%lld.pcd", 1538984233547259LL + (long long)k * 100000LL);
    io::write_pcd((fs::path(s.dir) / name).string(), d.frames[k].points, io::PcdEncoding::kBinaryCompressed);
    s.points += d.frames[k].points.size();
  }
  s.sensor = (root / "sensor.json").string();
  write_json_file(s.sensor, sensor_to_json(d.sensor));
  s.reference = (root / "reference.kitti.txt").string();
  io::write_kitti_poses(s.reference, gt_poses(d));
  s.config = (root / "config.json").string();
  write_json_file(s.config, test::tiny_sgnlf_overrides(true));
  return s;
}

workflow::ReconstructRequest request(const ScanFolder& s, const std::string& out) {
  workflow::ReconstructRequest r;
  r.scans = s.dir;
  r.run_dir = out;
  r.preset = "smoke";
  r.config = s.config;
  r.load.sensor = s.sensor;
  r.show_progress = false;
  return r;
}

bool same_poses(const std::vector<Pose>& a, const std::vector<Pose>& b, double tol) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (!a[i].matrix().isApprox(b[i].matrix(), tol) &&
        (a[i].matrix() - b[i].matrix()).cwiseAbs().maxCoeff() > tol)
      return false;
  return true;
}

}  // namespace

TEST_CASE("reconstruct: scans to poses, field, metrics, renders, cloud and report, resumable",
          "[workflow][reconstruct]") {
  auto& rt = test::runtime();
  const fs::path root = test::temp_dir("reconstruct");
  const ScanFolder s = write_scan_folder(root);
  const std::string out = (root / "run").string();

  // The folder loads without reference poses, at the names' 10 Hz.
  LoadOptions lo;
  lo.sensor = s.sensor;
  const Dataset plain = load_dataset(s.dir, lo);
  CHECK_FALSE(plain.has_reference_poses);
  CHECK(plain.frequency == "standard");
  CHECK(plain.frames[1].timestamp_s == Approx(0.1));

  const Json j = workflow::reconstruct(rt, request(s, out));
  for (const char* st : workflow::kReconstructStages) CHECK(j.at("stages").contains(st));
  CHECK_FALSE(j.contains("pose_errors"));
  // Where it trained, for the report's build row.
  CHECK(j.at("stages").at("train").at("context").at("build").at("git").is_object());
  CHECK(test::file_contents(out + "/report.html").find("not recorded in the run folder") ==
        std::string::npos);
  for (const char* f : {"odometry/odometry.kitti.txt", "odometry/odometry.tum.txt",
                        "odometry/odometry.json", "run.json", "summary.json", "metrics.json",
                        "trajectories/optimised.kitti.txt", "scene.ply", "scene.pcd", "report.html",
                        "reconstruct.json"})
    CHECK(fs::exists(fs::path(out) / f));
  CHECK_FALSE(fs::exists(fs::path(out) / "trajectories" / "gt.kitti.txt"));
  CHECK(fs::exists(fs::path(out) / "renders"));
  // The training started at the odometry.
  const auto odo = io::read_kitti_poses(out + "/odometry/odometry.kitti.txt");
  CHECK(same_poses(odo, io::read_kitti_poses(out + "/trajectories/initial.kitti.txt"), 1e-9));
  // The cloud holds every loaded point.
  CHECK(io::read_pcd(out + "/scene.pcd").size() == s.points);
  const Json metrics = load_json_file(out + "/metrics.json");
  CHECK_FALSE(metrics.contains("pose_metrics"));
  CHECK(metrics.at("reference_poses") == false);
  CHECK(metrics.at("metrics").at("depth_rmse").is_number());
  // The anatomy of the evaluated views: its totals are metrics.json's CD terms, its depth causes
  // metrics.json's depth MSE parts (means of linear terms), ours and the nearest scan's; the
  // report shows it.
  const Json anatomy = load_json_file(out + "/anatomy.json");
  // Null where metrics.json has null (the smoke field may predict no return: CD undefined).
  const auto same = [](const Json& a, const Json& b, double eps) {
    if (a.is_null() || b.is_null()) return a.is_null() && b.is_null();
    return a.get<double>() == Approx(b.get<double>()).epsilon(eps);
  };
  for (const char* who : {"model", "naive_baseline"}) {
    const Json& am = anatomy.at(who).at("mean");
    const Json& mm = std::string(who) == "model" ? metrics.at("metrics")
                                                 : metrics.at("naive_baseline").at("metrics");
    CHECK(same(am.at("cd_pred_to_gt/total"), mm.at("cd_pred_to_gt"), 1e-9));
    CHECK(same(am.at("cd_gt_to_pred/total"), mm.at("cd_gt_to_pred"), 1e-9));
    CHECK(same(am.at("depth_mse/cause/false"), mm.at("depth_mse_false"), 1e-9));
    CHECK(same(am.at("depth_mse/cause/missed"), mm.at("depth_mse_missed"), 1e-9));
    CHECK(am.at("depth_mse/train/<0.1m").is_number());
  }
  REQUIRE(anatomy.at("pictures").size() == metrics.at("per_frame").size());
  CHECK(fs::file_size(fs::path(out) / anatomy.at("pictures")[0].get<std::string>()) > 100);
  CHECK(test::file_contents(out + "/report.html").find("<h2>Error anatomy</h2>") != std::string::npos);

  // A rerun skips every stage: the checkpoint and the metrics stay as they were.
  const auto ck_time = fs::last_write_time(fs::path(out) / "checkpoints" / "latest.ckpt");
  const auto m_time = fs::last_write_time(fs::path(out) / "metrics.json");
  const Json again = workflow::reconstruct(rt, request(s, out));
  CHECK(again.at("stages") == j.at("stages"));
  CHECK(fs::last_write_time(fs::path(out) / "checkpoints" / "latest.ckpt") == ck_time);
  CHECK(fs::last_write_time(fs::path(out) / "metrics.json") == m_time);

  // A job killed before the anatomy renders the views itself: the same anatomy.
  {
    Json rec = load_json_file(out + "/reconstruct.json");
    for (const char* st : {"anatomy", "render", "cloud", "report"}) rec["stages"].erase(st);
    write_json_file(out + "/reconstruct.json", rec);
    fs::remove(fs::path(out) / "anatomy.json");
    workflow::reconstruct(rt, request(s, out));
    const Json again = load_json_file(out + "/anatomy.json");
    for (const char* k : {"cd_pred_to_gt/total", "cd_gt_to_pred/total", "depth_mse/total"})
      CHECK(same(again.at("model").at("mean").at(k), anatomy.at("model").at("mean").at(k), 1e-12));
  }

  // Killed after the training: the record ends at "train"; the rerun evaluates, renders and
  // writes the cloud and report again, and does not train.
  {
    Json rec = load_json_file(out + "/reconstruct.json");
    for (const char* st : {"evaluate", "anatomy", "render", "cloud", "report"}) rec["stages"].erase(st);
    write_json_file(out + "/reconstruct.json", rec);
    fs::remove(fs::path(out) / "metrics.json");
    fs::remove(fs::path(out) / "scene.ply");
  }
  const Json resumed = workflow::reconstruct(rt, request(s, out));
  CHECK(fs::last_write_time(fs::path(out) / "checkpoints" / "latest.ckpt") == ck_time);
  CHECK(fs::exists(fs::path(out) / "metrics.json"));
  CHECK(fs::exists(fs::path(out) / "scene.ply"));
  CHECK(resumed.at("stages").at("evaluate").at("metrics") == j.at("stages").at("evaluate").at("metrics"));

  // With reference poses the same job reports ATE/RPE of the odometry and of the optimised
  // poses, records them and rewrites the report with them; a later run without keeps them.
  const auto has = [&](const std::string& what) {
    return test::file_contents(out + "/report.html").find(what) != std::string::npos;
  };
  CHECK(has("No reference poses, so no ATE"));
  auto with_ref = request(s, out);
  with_ref.reference_poses = s.reference;
  const Json scored = workflow::reconstruct(rt, with_ref);
  REQUIRE(scored.contains("pose_errors"));
  CHECK(has("<th>odometry poses</th>"));
  CHECK_FALSE(has("No reference poses"));
  CHECK(load_json_file(out + "/reconstruct.json").at("pose_errors") == scored.at("pose_errors"));
  CHECK(workflow::reconstruct(rt, request(s, out)).at("pose_errors") == scored.at("pose_errors"));
  CHECK(scored.at("pose_errors").at("odometry").at("ate_m").get<double>() < 0.5);
  CHECK(scored.at("pose_errors").at("optimised").at("ate_m").get<double>() < 0.5);
  CHECK(scored.at("pose_errors").at("optimised").at("frames") == plain.frames.size());

  // Another request on the folder, a method that needs poses, a short reference file.
  auto other = request(s, out);
  other.seed = 2;
  CHECK_THROWS_WITH(workflow::reconstruct(rt, other), Catch::Contains("seed"));
  auto gt_method = request(s, (root / "run2").string());
  gt_method.method = "lidar-nerf";
  CHECK_THROWS_AS(workflow::reconstruct(rt, gt_method), ConfigError);
  auto short_ref = request(s, out);
  const std::string short_file = (root / "short.kitti.txt").string();
  io::write_kitti_poses(short_file, {Pose::Identity()});
  short_ref.reference_poses = short_file;
  CHECK_THROWS_WITH(workflow::reconstruct(rt, short_ref), Catch::Contains(short_file));

  // Scans without poses: no start from (perturbed) reference poses, no known-pose method.
  pipeline::PoseInitConfig pi;
  pi.init = "noisy";
  CHECK_THROWS_WITH(pipeline::initial_poses(plain, pi), Catch::Contains("without reference poses"));
  pi.init = "gt";
  CHECK_THROWS_AS(pipeline::initial_poses(plain, pi), ConfigError);
  pi.init = "identity";
  CHECK(pipeline::initial_poses(plain, pi).size() == plain.frames.size());
  const auto lidar_nerf = test::tiny_config();
  CHECK_THROWS_WITH(pipeline::make_run_scene(plain, lidar_nerf), Catch::Contains("without them"));
}

TEST_CASE("sgnlf reconstruct killed during training and run again equals the uninterrupted job",
          "[workflow][reconstruct][crash]") {
  const fs::path root = test::temp_dir("reconstruct_kill");
  const ScanFolder s = write_scan_folder(root);
  auto job = [&](const std::string& out, const std::string& fault) {
    return test::run_process({SGNLF_BIN, "reconstruct", "--scans", s.dir, "--out", out, "--preset",
                              "smoke", "--config", s.config, "--sensor", s.sensor},
                             out + ".log", {"SGNLF_FAULT_KILL=" + fault});
  };
  const std::string a = (root / "uninterrupted").string();
  const auto full = job(a, "");
  INFO(test::file_contents(a + ".log"));
  REQUIRE(full.exited);
  REQUIRE(full.code == 0);
  CHECK(test::file_contents(a + ".log").find("no reference poses") != std::string::npos);

  // Killed after step 17 of 28 (checkpoints every 7): the odometry is recorded, the training not.
  const std::string b = (root / "killed").string();
  const auto killed = job(b, "after-step@17");
  CHECK(killed.signal == SIGKILL);
  const Json rec = load_json_file(b + "/reconstruct.json");
  CHECK(rec.at("stages").contains("odometry"));
  CHECK_FALSE(rec.at("stages").contains("train"));
  CHECK(pipeline::load_checkpoint(pipeline::checkpoint_path(b)).step == 14);
  const auto again = job(b, "");
  INFO(test::file_contents(b + ".log"));
  REQUIRE(again.exited);
  REQUIRE(again.code == 0);

  CHECK(test::file_contents(pipeline::checkpoint_path(b)) ==
        test::file_contents(pipeline::checkpoint_path(a)));
  for (const char* f : {"/odometry/odometry.kitti.txt", "/trajectories/optimised.kitti.txt", "/scene.pcd"})
    CHECK(test::file_contents(b + f) == test::file_contents(a + f));
  CHECK(load_json_file(b + "/metrics.json").at("metrics") == load_json_file(a + "/metrics.json").at("metrics"));
}
