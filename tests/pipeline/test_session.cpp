// The run-folder flow behind `sgnlf train/render/eval` on a tiny synthetic sequence written to
// disk: run.json, checkpoint, summary, metrics of the model and the naive baseline, renders;
// a folder holding another run is refused.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/config.hpp"
#include "datasets/simulate.hpp"
#include "io/range_array.hpp"
#include "pipeline/run/anatomy_run.hpp"
#include "pipeline/run/evaluate.hpp"
#include "pipeline/model/render_view.hpp"
#include "pipeline/model/view_rules.hpp"
#include "pipeline/run/session.hpp"
#include "support/test_device.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::pipeline;
namespace fs = std::filesystem;

TEST_CASE("train, eval and render a run folder", "[pipeline][session][device]") {
  const std::string data = test::temp_dir("session_data") + "/seq";
  test::write_tiny_dataset(data);
  const std::string run_dir = test::temp_dir("session_run");
  const TrainRequest req = test::tiny_request("lidar-nerf", data, test::tiny_config(), run_dir, 5);
  const Json summary = train_run(test::runtime(), req);
  CHECK(summary.at("finished").get<bool>());
  CHECK(summary.at("end_step").get<long>() == 12);
  CHECK(fs::exists(run_dir + "/run.json"));
  CHECK(fs::exists(run_dir + "/summary.json"));

  LoadedRun run = load_run(test::runtime(), run_dir);
  CHECK(run.step == 12);
  const Json m = eval_run(run, run_dir);
  CHECK(fs::exists(run_dir + "/metrics.json"));
  REQUIRE(m.at("per_frame").size() == 1);
  CHECK(m.at("per_frame")[0].at("frame").get<int>() == run.dataset->frames[13].id);
  for (const char* k : {"cd", "fscore", "depth_rmse", "depth_psnr", "intensity_psnr"}) {
    CHECK(m.at("metrics").contains(k));
    CHECK(m.at("naive_baseline").at("metrics").contains(k));
  }
  CHECK(m.at("naive_baseline").at("metrics").at("fscore").get<double>() > 0.0);
  // Beside the expected depth: the median and "mix" depths' metrics, the mix's share of median
  // rays and the mean opacity; the naive baseline has no weights, so none of them.
  const Json& mx = m.at("metrics");
  for (const char* k : {"median_cd", "median_fscore", "mix_cd", "mix_depth_rmse"})
    CHECK(mx.at(k).get<double>() >= 0.0);
  CHECK(mx.at("mix_median_fraction").get<double>() >= 0.0);
  CHECK(mx.at("mix_median_fraction").get<double>() <= 0.5);  // above 10x the median: < half
  CHECK(mx.at("opacity_mean").get<double>() > 0.0);
  CHECK(mx.at("opacity_mean").get<double>() <= 1.0 + 1e-5);
  CHECK_FALSE(m.at("naive_baseline").at("metrics").contains("median_cd"));

  // The error anatomy of the same views (pipeline/run/anatomy_run.hpp): from eval_run's scored
  // views or rendered afresh, the same; its totals are metrics.json's CD terms.
  TestViewImages scored;
  eval_run(run, run_dir, nullptr, &scored);
  REQUIRE(scored.model.size() == 1);
  const Json anat = anatomy_run(run, run_dir, &scored);
  const Json fresh = anatomy_run(run, run_dir + "/anatomy_fresh");
  CHECK(fresh.at("model").at("mean") == anat.at("model").at("mean"));
  CHECK(fresh.at("naive_baseline").at("mean") == anat.at("naive_baseline").at("mean"));
  for (const char* k : {"cd_pred_to_gt", "cd_gt_to_pred"}) {
    CHECK(anat.at("model").at("mean").at(std::string(k) + "/total").get<double>() ==
          Approx(m.at("metrics").at(k).get<double>()).epsilon(1e-9));
    CHECK(anat.at("naive_baseline").at("mean").at(std::string(k) + "/total").get<double>() ==
          Approx(m.at("naive_baseline").at("metrics").at(k).get<double>()).epsilon(1e-9));
  }
  CHECK(anat.at("train_poses") == "reference");
  CHECK(fs::exists(run_dir + "/anatomy.json"));
  CHECK(fs::file_size(run_dir + "/" + anat.at("pictures")[0].get<std::string>()) > 100);
  TestViewImages short_set = scored;
  short_set.naive.clear();
  CHECK_THROWS_WITH(anatomy_run(run, run_dir, &short_set), Catch::Contains("0 naive views for 1 test frames"));

  const Json files = render_run(run, run_dir + "/renders");
  REQUIRE(files.size() == 1);
  CHECK(fs::file_size(files[0].at("png").get<std::string>()) > 100);
  CHECK(fs::exists(files[0].at("pred").get<std::string>()));
  // The naive baseline's view is the one `eval` scored.
  const RangeImage naive_img = io::read_range_npy(files[0].at("naive").get<std::string>());
  CHECK(naive_img.range == evaluate_naive(*run.dataset).images[0].range);

  // Chosen frames: a training frame with its own ground truth and no naive view, the test frame
  // as render_run renders it; an id the dataset lacks is refused by name.
  const Frame& train_frame = run.dataset->frames[size_t(run.dataset->split.train[0])];
  const Frame& test_frame = run.dataset->frames[13];
  const Json chosen = render_run(run, run_dir + "/chosen", nullptr, {train_frame.id, test_frame.id});
  REQUIRE(chosen.size() == 2);
  CHECK(chosen[0].at("frame").get<int>() == train_frame.id);
  CHECK_FALSE(chosen[0].at("test").get<bool>());
  CHECK_FALSE(chosen[0].contains("naive"));
  CHECK(io::read_range_npy(chosen[0].at("gt").get<std::string>()).range == train_frame.image.range);
  CHECK(chosen[1].at("test").get<bool>());
  CHECK(io::read_range_npy(chosen[1].at("pred").get<std::string>()).range ==
        io::read_range_npy(files[0].at("pred").get<std::string>()).range);
  CHECK(io::read_range_npy(chosen[1].at("naive").get<std::string>()).range == naive_img.range);
  const Json train_only = render_run(run, run_dir + "/train_only", nullptr, {train_frame.id});
  REQUIRE(train_only.size() == 1);
  CHECK_FALSE(train_only[0].contains("naive"));
  CHECK(io::read_range_npy(train_only[0].at("pred").get<std::string>()).range ==
        io::read_range_npy(chosen[0].at("pred").get<std::string>()).range);
  CHECK_THROWS_WITH(render_run(run, run_dir + "/chosen", nullptr, {-7}),
                    Catch::Contains("frame -7 is not in dataset"));

  // Novel views: at a test frame's own pose the render equals render_run's; a pose far outside
  // the scene still renders; an empty pose list is refused.
  const Pose T_test = run.dataset->frames[13].T_world_lidar;
  Pose T_far = T_test;
  T_far.translation() += Eigen::Vector3d(1e4, 0.0, 0.0);
  const Json views = render_poses(run, {T_test, T_far}, run_dir + "/views");
  REQUIRE(views.size() == 2);
  const RangeImage at_test = io::read_range_npy(views[0].at("npy").get<std::string>());
  const RangeImage from_run = io::read_range_npy(files[0].at("pred").get<std::string>());
  CHECK(at_test.range == from_run.range);
  CHECK(at_test.intensity == from_run.intensity);
  CHECK(at_test.ray_drop == from_run.ray_drop);
  CHECK(views[1].at("origin_normalised")[0].get<double>() > 1.0);
  CHECK(fs::file_size(views[1].at("png").get<std::string>()) > 100);
  CHECK_THROWS_AS(render_poses(run, {}, run_dir + "/views"), ConfigError);

  // A finer render sampling than training's loads the same checkpoint and is recorded.
  const int trained_samples = run.manifest.config.render.n_samples;
  LoadedRun fine = load_run(test::runtime(), run_dir, "", RenderSampling{2 * trained_samples, 8, "", ""});
  CHECK(fine.step == 12);
  CHECK(fine.manifest.config.render.n_samples == 2 * trained_samples);
  const Json mf = eval_run(fine, run_dir);
  CHECK(mf.at("render_sampling").at("n_samples").get<int>() == 2 * trained_samples);
  CHECK(mf.at("render_sampling").at("n_importance").get<int>() == 8);
  CHECK(std::isfinite(mf.at("metrics").at("depth_rmse").get<double>()));
  CHECK_THROWS_AS(load_run(test::runtime(), run_dir, "", RenderSampling{-1, -1, "", ""}), ConfigError);

  // The median-depth diagnostic changes the rendered depth only, and is recorded.
  LoadedRun med = load_run(test::runtime(), run_dir, "", RenderSampling{0, -1, "median", ""});
  CHECK(med.manifest.config.render.eval_depth == "median");
  const Json mm = eval_run(med, run_dir);
  CHECK(mm.at("render_sampling").at("depth") == "median");
  CHECK(mf.at("render_sampling").at("depth") == "expected");
  const RangeImage med_img = render_view(*med.model, *med.scene, T_test,
                                         med.manifest.config.schedule.render_chunk_rays);
  CHECK(med_img.ray_drop == from_run.ray_drop);
  CHECK(med_img.intensity == from_run.intensity);
  CHECK(med_img.range != from_run.range);
  CHECK_THROWS_AS(load_run(test::runtime(), run_dir, "", RenderSampling{0, -1, "mean", ""}),
                  ConfigError);

  // "mix": the median depth exactly where the render's variance exceeds the factor (GS-LiDAR's
  // 10 by default) times the frame's median, the expected depth elsewhere; the return mask and
  // intensity untouched. This short training's variances are too even for 10x (or 2x) to pick any ray,
  // so the factor here is 1 (the rays above the median).
  LoadedRun mixr = load_run(test::runtime(), run_dir, "", RenderSampling{0, -1, "mix", ""});
  mixr.manifest.config.render.eval_mix_factor = 1.0f;
  {
    const std::vector<float> trained = mixr.model->params();
    mixr.model = std::make_unique<LidarNerfModel>(test::runtime(), mixr.manifest.config,
                                                  float(mixr.scene->norm.scale),
                                                  model_capacity(mixr.manifest.config));
    mixr.model->set_params(trained);
  }
  DepthStats st;
  const RangeImage exp_img = render_view(*run.model, *run.scene, T_test,
                                         run.manifest.config.schedule.render_chunk_rays, -1,
                                         nullptr, &st);
  const RangeImage mix_img = render_view(*mixr.model, *mixr.scene, T_test,
                                         mixr.manifest.config.schedule.render_chunk_rays);
  const double thr = mix_variance_threshold(st.variance_m2, 1.0);
  size_t n_med = 0;
  for (size_t p = 0; p < mix_img.size(); ++p) {
    const bool med_px = double(st.variance_m2[p]) > thr;
    n_med += med_px;
    if (mix_img.range[p] != (med_px ? st.median_m[p] : exp_img.range[p])) FAIL("pixel " << p);
  }
  CHECK(n_med > 0);
  CHECK(n_med < mix_img.size());
  CHECK(mix_img.ray_drop == exp_img.ray_drop);
  CHECK(mix_img.intensity == exp_img.intensity);
  CHECK(eval_run(mixr, run_dir).at("render_sampling").at("depth") == "mix");

  // Out-of-range returns: with "drop", exactly the predicted returns outside the sensor's range
  // become drops. A sensor reaching 60 % of the farthest rendered return makes some.
  LoadedRun dropr = load_run(test::runtime(), run_dir, "", RenderSampling{0, -1, "", "drop"});
  CHECK(dropr.manifest.config.render.eval_drop_out_of_range);
  float far_m = 0.0f;
  for (size_t p = 0; p < exp_img.size(); ++p)
    if (exp_img.ray_drop[p] > 0.5f) far_m = std::max(far_m, exp_img.range[p]);
  dropr.scene->sensor.max_range_m = 0.6 * double(far_m);
  const RangeImage drop_img = render_view(*dropr.model, *dropr.scene, T_test,
                                          dropr.manifest.config.schedule.render_chunk_rays);
  size_t n_dropped = 0;
  for (size_t p = 0; p < drop_img.size(); ++p) {
    const bool out = exp_img.ray_drop[p] > 0.5f &&
                     !dropr.scene->sensor.in_range(double(exp_img.range[p]));
    n_dropped += out;
    if (drop_img.ray_drop[p] != (out ? 0.0f : exp_img.ray_drop[p])) FAIL("pixel " << p);
  }
  CHECK(n_dropped > 0);
  CHECK(drop_img.range == exp_img.range);
  CHECK_THROWS_AS(load_run(test::runtime(), run_dir, "", RenderSampling{0, -1, "", "cut"}),
                  ConfigError);

  // A config's eval sampling is what eval uses unless overridden; training does not see it.
  TrainRequest ev = req;
  ev.run_dir = test::temp_dir("session_run_eval_sampling");
  ev.manifest.config.render.eval_samples = 3 * trained_samples;
  ev.manifest.config.render.eval_importance = 5;
  train_run(test::runtime(), ev);
  LoadedRun by_config = load_run(test::runtime(), ev.run_dir);
  CHECK(by_config.manifest.config.render.n_samples == 3 * trained_samples);
  CHECK(by_config.manifest.config.render.n_importance == 5);
  CHECK(by_config.model->params() == run.model->params());  // same training
  LoadedRun overridden = load_run(test::runtime(), ev.run_dir, "", RenderSampling{0, 2, "", ""});
  CHECK(overridden.manifest.config.render.n_samples == 3 * trained_samples);
  CHECK(overridden.manifest.config.render.n_importance == 2);

  TrainRequest other = req;
  other.manifest.seed = 6;
  CHECK_THROWS_AS(train_run(test::runtime(), other), ConfigError);

  // Dataset options (here test frames by position) are recorded in run.json and reused by eval;
  // a folder trained with other options is refused, and a bad option leaves no folder behind.
  TrainRequest split = req;
  split.run_dir = test::temp_dir("session_run_test_frames");
  split.manifest.data_options.test_frames = {3, 9};
  train_run(test::runtime(), split);
  CHECK(load_json_file(split.run_dir + "/run.json").at("dataset_options") ==
        Json{{"test_frames", {3, 9}}});
  CHECK_FALSE(load_json_file(run_dir + "/run.json").contains("dataset_options"));
  LoadedRun by_position = load_run(test::runtime(), split.run_dir);
  CHECK(by_position.dataset->split.test == std::vector<int>{3, 9});
  const Json ms = eval_run(by_position, split.run_dir);
  REQUIRE(ms.at("per_frame").size() == 2);
  CHECK(ms.at("per_frame")[0].at("frame").get<int>() == by_position.dataset->frames[3].id);
  CHECK(ms.at("per_frame")[1].at("frame").get<int>() == by_position.dataset->frames[9].id);
  TrainRequest changed = split;
  changed.manifest.data_options.test_frames = {4};
  CHECK_THROWS_WITH(train_run(test::runtime(), changed), Catch::Contains("dataset options"));
  TrainRequest bad = req;
  bad.run_dir = test::temp_dir("session_run_bad_option");
  fs::remove_all(bad.run_dir);
  bad.manifest.data_options.test_frames = {40};
  CHECK_THROWS_WITH(train_run(test::runtime(), bad), Catch::Contains("position 40"));
  CHECK_FALSE(fs::exists(fs::path(bad.run_dir) / "run.json"));
}

TEST_CASE("a run folder of config shape 1 is refused with what to do", "[pipeline][session]") {
  const std::string dir = test::temp_dir("session_run_shape1");
  write_json_file(dir + "/run.json",
                  Json{{"method", "sg-nlf"}, {"preset", "quick"}, {"dataset", "x"}, {"seed", 1},
                       {"config_hash", "e3dab93155649326"},
                       {"config", {{"field", {{"levels", 14}, {"features_per_level", 2}}}}}});
  try {
    read_manifest(dir);
    FAIL("an old run folder was read");
  } catch (const ConfigError& e) {
    CHECK_THAT(e.what(), Catch::Contains(dir + "/run.json") && Catch::Contains("older sgnlf") &&
                             Catch::Contains("field.grid"));
  }
}
