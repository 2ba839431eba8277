// LiDAR4D's ray-drop refinement as a stage (run/ray_drop_stage.hpp): the training frames it
// renders, the U-Net trained on a tiny LiDAR4D field's renders (BCE falls, bit-identical from one
// seed), saved and loaded bit-exactly, refused under another U-Net config, changing the return
// probability only; and in a run folder: trained once a run finishes, reused when it is resumed,
// applied by eval.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <functional>

#include "core/config.hpp"
#include "datasets/protocol.hpp"
#include "io/range_array.hpp"
#include "pipeline/model/render_view.hpp"
#include "pipeline/run/ray_drop_stage.hpp"
#include "pipeline/run/session.hpp"
#include "pipeline/train/step_policy.hpp"
#include "pipeline/train/trainer.hpp"
#include "support/test_device.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::pipeline;
namespace fs = std::filesystem;

namespace {

// The tiny LiDAR4D field after the smoke schedule's 16 steps on ground-truth poses.
std::unique_ptr<LidarNerfModel> trained_field(const Scene& scene, const TrainConfig& c) {
  auto model = std::make_unique<LidarNerfModel>(test::runtime(), c, float(scene.norm.scale),
                                                model_capacity(c));
  GroundTruthPoseStep gt(scene, c);
  TrainOptions opt;
  opt.run_dir = test::temp_dir("ray_drop_field");
  opt.seed = 3;
  opt.show_progress = false;
  opt.policy = &gt;
  train(*model, scene, c, opt);
  return model;
}

RayDropRefinementConfig tiny_refinement(int steps) {
  RayDropRefinementConfig rc;
  rc.frames = 2;
  rc.unet.channels = 16;
  rc.unet.depth = 2;
  rc.unet.steps = steps;
  return rc;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("ray-drop stage: training frames evenly spaced, first and last included",
          "[pipeline][lidar4d]") {
  const std::vector<int> train = {0, 2, 4, 6, 8, 10, 12};
  CHECK(ray_drop_frames(train, 0) == train);
  CHECK(ray_drop_frames(train, 7) == train);
  CHECK(ray_drop_frames(train, 9) == train);
  CHECK(ray_drop_frames(train, 1) == std::vector<int>{0});
  CHECK(ray_drop_frames(train, 2) == std::vector<int>{0, 12});
  CHECK(ray_drop_frames(train, 3) == std::vector<int>{0, 6, 12});
  CHECK(ray_drop_frames(train, 4) == std::vector<int>{0, 4, 8, 12});
  const std::vector<int>& tiny = test::tiny_dataset().split.train;
  for (int k = 2; k < int(tiny.size()); ++k) {
    const std::vector<int> f = ray_drop_frames(tiny, k);
    REQUIRE(f.size() == size_t(k));
    CHECK(f.front() == tiny.front());
    CHECK(f.back() == tiny.back());
    CHECK(std::is_sorted(f.begin(), f.end()));
    CHECK(std::adjacent_find(f.begin(), f.end()) == f.end());
  }
}

TEST_CASE("ray-drop stage: trains on the training renders, saves, loads, refines ray drop only",
          "[pipeline][lidar4d]") {
  const Dataset& d = test::tiny_dataset();
  const Scene scene = make_scene(d);
  const TrainConfig c = test::tiny_lidar4d();
  const auto model = trained_field(scene, c);
  const std::vector<Pose> poses = gt_poses(d);
  const RayDropRefinementConfig rc = tiny_refinement(20);
  RayDropStage a(test::runtime(), rc), b(test::runtime(), rc);
  const Json sa = a.train(*model, scene, d, poses, 512);
  INFO(sa.dump());
  REQUIRE(sa.at("frames").size() == 2);
  CHECK(sa.at("frames")[0].get<int>() == d.frames[size_t(d.split.train.front())].id);
  CHECK(sa.at("frames")[1].get<int>() == d.frames[size_t(d.split.train.back())].id);
  CHECK(sa.at("steps").get<int>() == 20);
  CHECK(sa.at("final_bce").get<double>() < sa.at("initial_bce").get<double>());
  const Json sb = b.train(*model, scene, d, poses, 512);
  CHECK(sb.at("final_bce").get<double>() == sa.at("final_bce").get<double>());

  // On a test view: the same output from both stages and from a repeat, range and intensity
  // untouched, probabilities in [0, 1].
  const int t = d.split.test.front();
  const RangeImage view = render_view(*model, scene, poses[size_t(t)], 512, t);
  RangeImage ra = view, rb = view, ra2 = view;
  a.apply(ra);
  b.apply(rb);
  a.apply(ra2);
  CHECK(ra.ray_drop == rb.ray_drop);
  CHECK(ra.ray_drop == ra2.ray_drop);
  CHECK(ra.ray_drop != view.ray_drop);
  CHECK(ra.range == view.range);
  CHECK(ra.intensity == view.intensity);
  CHECK(*std::min_element(ra.ray_drop.begin(), ra.ray_drop.end()) >= 0.0f);
  CHECK(*std::max_element(ra.ray_drop.begin(), ra.ray_drop.end()) <= 1.0f);

  // Saved and loaded into a fresh stage (at its initial parameters): bit-identical output.
  const std::string file = test::temp_dir("ray_drop_stage") + "/unet.bin";
  a.save(file);
  RayDropStage fresh(test::runtime(), rc);
  RangeImage rf = view;
  fresh.apply(rf);
  CHECK(rf.ray_drop != ra.ray_drop);
  fresh.load(file);
  rf = view;
  fresh.apply(rf);
  CHECK(rf.ray_drop == ra.ray_drop);

  // Another U-Net config (another schedule, another width) refuses the file, naming it; a
  // missing file is named too.
  RayDropStage longer(test::runtime(), tiny_refinement(21));
  const std::string e1 = error_of([&] { longer.load(file); });
  CHECK(e1.find(file) != std::string::npos);
  CHECK(e1.find("U-Net config") != std::string::npos);
  RayDropRefinementConfig wide = rc;
  wide.unet.channels = 32;
  RayDropStage wider(test::runtime(), wide);
  CHECK(error_of([&] { wider.load(file); }).find(file) != std::string::npos);
  CHECK(error_of([&] { fresh.load(file + ".missing"); }).find(file + ".missing") !=
        std::string::npos);
  // All training frames for frames = 0.
  RayDropRefinementConfig all = tiny_refinement(2);
  all.frames = 0;
  RayDropStage every(test::runtime(), all);
  CHECK(every.train(*model, scene, d, poses, 512).at("frames").size() == d.split.train.size());
}

TEST_CASE("ray-drop stage in a run folder: after a finished run, reused on resume, applied by eval",
          "[pipeline][lidar4d][session]") {
  const std::string data = test::temp_dir("ray_drop_data") + "/seq";
  test::write_tiny_dataset(data);
  const std::string run_dir = test::temp_dir("ray_drop_run");
  // Evaluation samples more finely than training: the stage renders as evaluation does.
  const TrainConfig c = test::tiny_lidar4d(Json{{"render", {{"eval_samples", 24}}}});
  REQUIRE(c.ray_drop_refinement());
  const std::string file = ray_drop_unet_path(run_dir);
  // Stopped early: no stage; eval goes on without the U-Net.
  const Json part = train_run(test::runtime(), test::tiny_request("lidar4d", data, c, run_dir, 4, 8));
  CHECK_FALSE(part.at("finished").get<bool>());
  CHECK_FALSE(part.contains("ray_drop_refinement"));
  CHECK_FALSE(fs::exists(file));
  {
    LoadedRun run = load_run(test::runtime(), run_dir);
    CHECK(run.ray_drop == nullptr);
    CHECK_FALSE(eval_run(run, run_dir).at("ray_drop_refinement").get<bool>());
  }
  // Finished: the stage trains and saves the U-Net; summary.json records it.
  const Json done = train_run(test::runtime(), test::tiny_request("lidar4d", data, c, run_dir, 4));
  REQUIRE(done.at("finished").get<bool>());
  REQUIRE(done.contains("ray_drop_refinement"));
  const Json& rd = done.at("ray_drop_refinement");
  CHECK(rd.at("frames").size() == 2);
  CHECK(rd.at("steps").get<int>() == c.lidar4d->refine->unet.steps);
  CHECK(rd.at("file").get<std::string>() == file);
  CHECK(fs::exists(file));
  CHECK(load_json_file(run_dir + "/summary.json").contains("ray_drop_refinement"));
  // eval and render apply it.
  LoadedRun run = load_run(test::runtime(), run_dir);
  REQUIRE(run.ray_drop != nullptr);
  const Json m = eval_run(run, run_dir);
  CHECK(m.at("ray_drop_refinement").get<bool>());
  CHECK(load_json_file(run_dir + "/metrics.json").at("ray_drop_refinement").get<bool>());
  const int t = run.dataset->split.test.front();
  RangeImage expect = render_view(*run.model, *run.scene, run.T_world_lidar[size_t(t)],
                                  run.manifest.config.schedule.render_chunk_rays, t);
  run.ray_drop->apply(expect);
  const Json views = render_poses(run, {run.T_world_lidar[size_t(t)]}, run_dir + "/views");
  const RangeImage got = io::read_range_npy(views[0].at("npy").get<std::string>());
  CHECK(got.ray_drop == expect.ray_drop);
  CHECK(got.range == expect.range);
  // Resumed when finished: the file is loaded, not retrained.
  const auto stamp = fs::last_write_time(file);
  const Json again = train_run(test::runtime(), test::tiny_request("lidar4d", data, c, run_dir, 4));
  CHECK(again.at("ray_drop_refinement").at("reused").get<bool>());
  CHECK(fs::last_write_time(file) == stamp);
}
