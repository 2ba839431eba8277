// The pose-free machinery (issue "Pose-free joint optimisation"): the gradient of one whole
// training step's loss with respect to the pose correction ξ of its frame against central
// finite differences; pose-free run folders (initial/optimised trajectories, pose metrics,
// frozen-pose control, exact resume with the poses); bad pose options.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/config.hpp"
#include "datasets/simulate.hpp"
#include "pipeline/methods/registry.hpp"
#include "pipeline/train/pose_set.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "pipeline/run/run_dir.hpp"
#include "pipeline/run/session.hpp"
#include "pipeline/train/trainer.hpp"
#include "render/pose_gradient.hpp"
#include "support/test_device.hpp"
#include "pose_step_fd.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::pipeline;
namespace fs = std::filesystem;

namespace {

// GeoNLF's smoke preset shrunk to the tiny sequence.
TrainConfig tiny_pose_free(const std::string& method, const Json& extra = Json::object()) {
  Json o{{"schedule", {{"iterations", 28}, {"checkpoint_every", 7}, {"log_every", 7},
                       {"rays_per_batch", 128}, {"render_chunk_rays", 512}}},
         {"render", {{"n_samples", 24}}},
         {"geometric", {{"first_steps", 5}, {"steps_per_epoch", 2.0},
                        {"optimizer", {{"points_per_frame", 400}}}}}};
  // A method without the geometric stage (the frozen control) refuses its section.
  if (!resolve_config(method, "smoke").geometric_stage()) o.erase("geometric");
  return resolve_config(method, "smoke", merge_config_json(o, extra));
}


}  // namespace

TEST_CASE("one training step's loss: analytic dL/dxi of its frame matches finite differences",
          "[pipeline][posefree][device]") {
  const Dataset& d = test::tiny_dataset();
  // Uniform samples only (GeoNLF's sampling): importance-sample depths are held fixed in the
  // backward pass, which finite differences would not see.
  const TrainConfig c = test::tiny_config(Json{{"render", {{"n_importance", 0}, {"n_samples", 48}}},
                                          {"schedule", {{"iterations", 40}}}});
  const Scene scene = make_scene(d);
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), 512);
  TrainOptions opt;
  opt.run_dir = test::temp_dir("posefree_fd");
  opt.show_progress = false;
  opt.resume = false;
  train(model, scene, c, opt);  // a field with structure, so the loss depends on the pose
  // An arbitrary non-zero correction on top of the frame's pose: the gradient is exact there too.
  Vec6 xi0;
  xi0 << 0.01, -0.02, 0.015, 0.004, -0.003, 0.002;
  // eps in radians / normalised units (5e-5 ≈ 1 cm here). The hash grid's gradient is piecewise
  // constant, so larger steps cross cell boundaries (1e-3 is off by 8 % of the largest
  // component on this state); below ~2e-5 the float loss's rounding shows.
  test::check_pose_step_gradients(test::pose_step_gradients(model, scene, c, 41, xi0, 5e-5));
}

TEST_CASE("PoseSet: corrections, per-frame Adam, set_pose and exact state round trip",
          "[pipeline][posefree]") {
  std::vector<Pose> init(3, Pose::Identity());
  init[1].translation() = Vec3(1, 2, 3);
  PoseOptimConfig pc;
  PoseSet ps(init, pc);
  CHECK(ps.pose(1).isApprox(init[1]));
  Vec6 g;
  g << 1, 0, 0, 0, -1, 0;
  ps.step(1, g, 0.0);
  // Adam's first step moves each component by lr against the gradient's sign.
  CHECK(ps.correction(1)[0] == Approx(-pc.lr_rot).epsilon(1e-6));
  CHECK(ps.correction(1)[4] == Approx(pc.lr_trans).epsilon(1e-6));
  CHECK(ps.correction(0).isZero());  // other frames do not move
  Pose target = init[2];
  target.linear() = exp_so3(Vec3(0.1, -0.2, 0.3));
  target.translation() = Vec3(-4, 5, 6);
  ps.set_pose(2, target);
  CHECK(ps.pose(2).isApprox(target, 1e-12));
  PoseSet copy(init, pc);
  const auto arrays = ps.state_arrays();
  copy.load_state([&](const std::string& name, size_t n) {
    for (const auto& [k, v] : arrays)
      if (k == name) {
        REQUIRE(v.size() == n);
        return v;
      }
    FAIL("missing " << name);
    return std::vector<float>{};
  });
  for (size_t i = 0; i < 3; ++i) CHECK(copy.correction(i) == ps.correction(i));
  Pose bad = target;
  bad.translation().x() = std::nan("");
  CHECK_THROWS_AS(ps.set_pose(0, bad), NumericError);
}

TEST_CASE("pose-free run folder: trajectories, pose metrics, frozen control, exact resume",
          "[pipeline][posefree][session][device]") {
  const std::string data = test::temp_dir("posefree_data") + "/seq";
  test::write_tiny_dataset(data);
  auto run = [&](const std::string& method, const std::string& dir, long stop_at, bool resume) {
    return train_run(test::runtime(), test::tiny_request(method, data, tiny_pose_free(method), dir,
                                                         3, stop_at, resume));
  };
  const std::string full = test::temp_dir("posefree_full");
  const Json s = run("geonlf", full, -1, false);
  CHECK(s.at("finished").get<bool>());
  for (const char* f : {"gt.kitti.txt", "initial.kitti.txt", "optimised.kitti.txt", "optimised.tum.txt",
                        "top_view.svg"})
    CHECK(fs::exists(full + "/trajectories/" + f));
  CHECK(fs::exists(full + "/geometric_log.jsonl"));
  const double ate0 = s.at("initial_pose_metrics").at("ate_m").get<double>();
  const double ate = s.at("pose_metrics").at("ate_m").get<double>();
  CHECK(ate0 > 1.0);   // the protocol's noisy start (σ 2 m per axis)
  CHECK(ate < ate0);   // the poses moved towards the truth
  LoadedRun lr = load_run(test::runtime(), full);
  CHECK(lr.pose_free);
  const Json m = eval_run(lr, full);
  CHECK(m.at("pose_metrics").at("ate_m").get<double>() == Approx(ate).epsilon(1e-12));
  CHECK(m.at("pose_init").get<std::string>() == "noisy");

  // Killed after step 10 and resumed: bit-identical poses and parameters.
  const std::string part = test::temp_dir("posefree_part");
  run("geonlf", part, 10, false);
  run("geonlf", part, -1, true);
  LoadedRun resumed = load_run(test::runtime(), part);
  for (size_t i = 0; i < lr.T_world_lidar.size(); ++i)
    CHECK(resumed.T_world_lidar[i].matrix() == lr.T_world_lidar[i].matrix());
  CHECK(resumed.model->params() == lr.model->params());

  // The control keeps its initial poses.
  const std::string frozen = test::temp_dir("posefree_frozen");
  const Json f = run("geonlf-frozen", frozen, -1, false);
  CHECK(f.at("pose_metrics").at("ate_m").get<double>() == Approx(ate0).epsilon(1e-9));
}

TEST_CASE("photometric pose updates begin at pose_optim.start_step",
          "[pipeline][posefree][session][device]") {
  const std::string data = test::temp_dir("posefree_start_data") + "/seq";
  test::write_tiny_dataset(data);
  // The geometric stage off, so that only the photometric updates move the poses.
  auto ate_with = [&](long start_step, const std::string& name) {
    const Json extra{{"geometric", nullptr},
                     {"pose_optim", {{"start_step", start_step}}}};
    const Json s = train_run(test::runtime(),
                             test::tiny_request("geonlf", data, tiny_pose_free("geonlf", extra),
                                                test::temp_dir(name), 3, -1, false));
    return std::make_pair(s.at("initial_pose_metrics").at("ate_m").get<double>(),
                          s.at("pose_metrics").at("ate_m").get<double>());
  };
  const auto [ate0, never] = ate_with(28, "posefree_start_never");  // = iterations: no update
  CHECK(never == Approx(ate0).epsilon(1e-9));  // the poses' round trip through the scene's frame
  const auto [ate0_half, half] = ate_with(14, "posefree_start_half");
  const auto [ate0_all, all] = ate_with(0, "posefree_start_all");
  CHECK(ate0_half == ate0);
  CHECK(ate0_all == ate0);
  CHECK(std::abs(half - ate0) > 1e-6);  // moved after step 14 …
  CHECK(std::abs(half - all) > 1e-6);   // … and not as the run updating from step 0
  CHECK_THROWS_WITH(tiny_pose_free("geonlf", Json{{"pose_optim", {{"start_step", -1}}}}),
                    Catch::Contains("start_step"));
}

TEST_CASE("pose-free options: unknown init, ground-truth methods, too few frames",
          "[pipeline][posefree]") {
  CHECK_THROWS_WITH(resolve_config("geonlf", "smoke", Json{{"poses", {{"init", "random"}}}}),
                    Catch::Contains("'init' = \"random\""));
  CHECK_THROWS_WITH(resolve_config("lidar-nerf", "smoke", Json{{"poses", {{"init", "noisy"}}}}),
                    Catch::Contains("poses"));
  CHECK_THROWS_WITH(resolve_config("nonsense", "smoke"), Catch::Contains("unknown method"));
  Dataset d = test::tiny_dataset();
  d.split.train.insert(d.split.train.end(), d.split.test.begin(), d.split.test.end());
  d.split.test.clear();
  CHECK_THROWS_WITH(make_run_scene(d, tiny_pose_free("geonlf")), Catch::Contains("test frames"));
}

TEST_CASE("geometric.reseed runs after the coarse alignment and is logged",
          "[pipeline][posefree][session][device]") {
  const std::string data = test::temp_dir("posefree_reseed_data") + "/seq";
  test::write_tiny_dataset(data);
  auto first_line = [&](const Json& extra, const std::string& name) {
    const std::string dir = test::temp_dir(name);
    Json o = merge_config_json(Json{{"schedule", {{"iterations", 7}}}}, extra);
    train_run(test::runtime(),
              test::tiny_request("geonlf", data, tiny_pose_free("geonlf", o), dir, 3, -1, false));
    std::ifstream f(dir + "/geometric_log.jsonl");
    std::string line;
    REQUIRE(std::getline(f, line));
    return Json::parse(line);
  };
  const Json off = first_line(Json::object(), "posefree_reseed_off");
  CHECK_FALSE(off.contains("reseed"));
  // A low threshold, so that the tiny run's uneven steps give candidates: the trials are
  // reported with the losses they were decided on.
  const Json on = first_line(
      Json{{"geometric", {{"reseed", {{"min_difference_m", 0.01}, {"steps", 10}, {"max_rounds", 1}}}}}},
      "posefree_reseed_on");
  REQUIRE(on.contains("reseed"));
  int kept = 0;
  for (const auto& t : on["reseed"]["trials"]) {
    CHECK(t["edge"][1].get<int>() == t["edge"][0].get<int>() + 1);
    for (const char* k : {"crossing_before", "crossing_after", "rest_before", "rest_after"})
      CHECK(t[k].get<double>() >= 0.0);
    kept += t["kept"].get<bool>() ? 1 : 0;
  }
  CHECK(on["reseed"]["kept"].get<int>() == kept);
}

TEST_CASE("geometric.refine runs after the coarse alignment, lowers its own loss and is logged",
          "[pipeline][posefree][session][device]") {
  const std::string data = test::temp_dir("posefree_refine_data") + "/seq";
  test::write_tiny_dataset(data);
  auto run = [&](const Json& extra, const std::string& name) {
    const std::string dir = test::temp_dir(name);
    // 28 steps (tiny_pose_free's): an epoch is the 13 training frames, so epoch 1 starts at
    // progress 0.46, before stop_progress 0.6, and takes lround(10 · (1 − 0.46 / 0.6)) = 2 steps.
    const Json o = merge_config_json(Json{{"geometric", {{"steps_per_epoch", 10.0}}}}, extra);
    train_run(test::runtime(),
              test::tiny_request("geonlf", data, tiny_pose_free("geonlf", o), dir, 3, -1, false));
    std::ifstream f(dir + "/geometric_log.jsonl");
    std::vector<Json> lines;
    for (std::string line; std::getline(f, line);) lines.push_back(Json::parse(line));
    REQUIRE(lines.size() >= 2);  // the coarse alignment and at least one later epoch
    return lines;
  };
  auto refine = [](bool later) {
    return Json{{"geometric", {{"refine", {{"steps", 20},
                                           {"later_epochs", later},
                                           {"optimizer", {{"points_per_frame", 400},
                                                          {"edge_offsets", {1, 2, 3}}}}}}}}};
  };
  const auto off = run(Json::object(), "posefree_refine_off");
  CHECK_FALSE(off[0].contains("refine"));
  const auto on = run(refine(true), "posefree_refine_on");
  REQUIRE(on[0].contains("refine"));
  const Json& r = on[0]["refine"];
  CHECK(r["steps"] == 20);
  CHECK(r["residual"] == "point_to_plane");
  CHECK(r["loss_after"].get<double>() < r["loss_before"].get<double>());
  CHECK(r["max_frame_move_m"].get<double>() > 0.0);
  // The coarse alignment before it is the same run; the stage's own loss is re-evaluated after.
  CHECK(on[0]["loss_before"] == off[0]["loss_before"]);
  CHECK(on[0]["loss_after"] != off[0]["loss_after"]);
  // later_epochs: the later epochs' steps take the refine's estimator (its loss, not the
  // stage's point-to-point one); without it they keep the stage's, from the same refined start.
  const auto only_first = run(refine(false), "posefree_refine_first");
  CHECK(only_first[0]["loss_after"] == on[0]["loss_after"]);
  CHECK(on[1].value("estimator", "") == "refine");
  CHECK_FALSE(only_first[1].contains("estimator"));
  CHECK(on[1]["loss_before"] != only_first[1]["loss_before"]);
}
