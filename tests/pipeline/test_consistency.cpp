// SG-NLF's adversarial cross-frame consistency in pose-free training (how a term's own pass
// joins the step's Adam update: test_loss_terms.cpp): the gradient of L_con with respect to a
// frame's ξ through render → reprojection → discriminator against finite differences; a run
// folder of `sg-nlf` (L_D/L_con logged, exact resume of field, discriminator and poses); the
// "consistency" section's validation.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/config.hpp"
#include "pipeline/train/consistency_schedule.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "pipeline/run/run_dir.hpp"
#include "pipeline/run/session.hpp"
#include "pipeline/train/trainer.hpp"
#include "support/test_device.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::pipeline;
namespace fs = std::filesystem;

namespace {

// The tiny sequence is 16 × 128: frame j's image at every 2nd column (16 × 64), one scale.
TrainConfig tiny_sgnlf(const Json& extra = Json::object()) {
  return resolve_config("sg-nlf", "smoke",
                        merge_config_json(test::tiny_sgnlf_overrides(true), extra));
}

}  // namespace

TEST_CASE("consistency term: analytic dL_con/dxi through render, reprojection and "
          "discriminator matches finite differences",
          "[pipeline][consistency][device]") {
  const Dataset& ds = test::tiny_dataset();
  // λ_con 1: the term's gradient is dL_con/dξ itself; a wider initialisation gives the
  // discriminator gradients well above float rounding of L_con.
  TrainConfig c = tiny_sgnlf(Json{
      {"render", {{"n_samples", 48}}},
      {"schedule", {{"iterations", 40}}},
      {"consistency", {{"weight", 1.0}, {"discriminator", {{"init_std", 0.3}}}}}});
  const Scene scene = make_scene(ds);
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), 512);
  model.set_fusion_weight(1.0f);
  TrainOptions opt;
  opt.run_dir = test::temp_dir("consistency_fd");
  opt.show_progress = false;
  opt.resume = false;
  train(model, scene, c, opt);  // a field with structure (ground-truth poses)

  ConsistencyTerm term(test::runtime(), scene, *c.consistency, 512);
  // Each run in a pass of its own (seed 7, step 40), as a training step gives it.
  const RayBatch no_batch;
  auto run = [&](const ConsistencyPair& q, bool disc, bool pose_grads) {
    FieldPass field(model, no_batch, 7, 40);
    return term.run(field, q, disc, pose_grads);
  };
  ConsistencyPair p;
  p.i = 4, p.j = 5;
  p.T_init_i = scene.T_world_lidar[4], p.T_init_j = scene.T_world_lidar[5];
  p.xi_i << 0.004, -0.003, 0.002, 0.01, -0.006, 0.004;
  p.xi_j << -0.002, 0.003, 0.001, -0.005, 0.008, 0.002;
  for (int k = 0; k < 3; ++k) run(p, true, false);  // a trained discriminator
  const ConsistencyResult base = run(p, false, true);
  const std::vector<int> winners = term.last_reprojection().winner;
  REQUIRE(base.rendered_points > 100);
  REQUIRE(base.coverage > 0.05);

  // Finite differences where the discrete choices (which source pixel wins each target pixel,
  // which depths pass the return threshold) stay as at ξ: the pixel choice is not
  // differentiated (render/cross_frame_reprojection.hpp), so the step must keep them, which
  // holds only for steps of ~1e-5 here. L_con is a float sum of a few thousand logits of size
  // ~5 (ulp 5e-7), so a two-point difference at that step has ~5 % noise: the slope is the
  // least-squares fit over 17 points in [−eps, eps] (all with the winners of ξ), for the
  // largest eps of the list where all keep them.
  auto numeric = [&](bool frame_i, int k) {
    for (double eps : {4e-5, 2e-5, 1e-5, 5e-6, 2.5e-6}) {
      double sxy = 0.0, sxx = 0.0;
      bool same = true;
      for (int m = -8; m <= 8 && same; ++m) {
        ConsistencyPair q = p;
        const double x = eps * m / 8.0;
        (frame_i ? q.xi_i : q.xi_j)[k] += x;
        const double l = run(q, false, false).l_con;
        same = term.last_reprojection().winner == winners;
        sxy += x * l, sxx += x * x;
      }
      if (same) return sxy / sxx;  // Σx = 0: the slope of the least-squares line
    }
    FAIL("no step keeps the winners of frame " << (frame_i ? "i" : "j") << ", component " << k);
    return 0.0;
  };
  Vec6 num_i, num_j;
  for (int k = 0; k < 6; ++k) num_i[k] = numeric(true, k);
  for (int k = 3; k < 6; ++k) num_j[k] = numeric(false, k);
  INFO("analytic i " << base.grad_xi_i.transpose() << "\nnumeric  i " << num_i.transpose());
  INFO("analytic j " << base.grad_xi_j.transpose() << "\nnumeric  j " << num_j.tail<3>().transpose());
  const double scale_i = num_i.cwiseAbs().maxCoeff();
  REQUIRE(scale_i > 1e-4);
  for (int k = 0; k < 6; ++k) CHECK(std::abs(base.grad_xi_i[k] - num_i[k]) < 0.05 * scale_i);
  CHECK(base.grad_xi_i.dot(num_i) > 0.98 * base.grad_xi_i.norm() * num_i.norm());
  // Frame j: translation through the reprojection; its rotation gets no gradient.
  const double scale_j = num_j.tail<3>().cwiseAbs().maxCoeff();
  REQUIRE(scale_j > 1e-5);
  for (int k = 3; k < 6; ++k) CHECK(std::abs(base.grad_xi_j[k] - num_j[k]) < 0.05 * scale_j);
  CHECK(base.grad_xi_j.head<3>().norm() == 0.0);
}

TEST_CASE("sg-nlf run folder: consistency logged, exact resume of field, discriminator, poses",
          "[pipeline][consistency][session][device]") {
  const std::string data = test::temp_dir("consistency_data") + "/seq";
  test::write_tiny_dataset(data);
  auto run = [&](const std::string& dir, long stop_at, bool resume) {
    return train_run(test::runtime(),
                     test::tiny_request("sg-nlf", data, tiny_sgnlf(), dir, 3, stop_at, resume));
  };
  const std::string full = test::temp_dir("consistency_full");
  const Json s = run(full, -1, false);
  CHECK(s.at("finished").get<bool>());
  // Steps 4, 6, …, 26 whose batch frame has a trainable neighbour (test frame 13 is pose-only).
  CHECK(s.at("consistency_steps").get<long>() >= 8);
  CHECK(s.at("consistency_seconds").get<double>() > 0.0);
  std::ifstream log(full + "/train_log.jsonl");
  std::string line;
  int logged = 0, with_points = 0;
  while (std::getline(log, line)) {
    const Json j = Json::parse(line);
    if (!j.contains("consistency")) continue;
    const Json& k = j.at("consistency");
    ++logged;
    // λ_con·L_con with the other terms' values, out of the total (loss_report.hpp).
    CHECK(j.at("loss").at("consistency").get<double>() ==
          tiny_sgnlf().consistency->weight * k.at("l_con").get<double>());
    CHECK(std::isfinite(k.at("l_d").get<double>()));
    CHECK(k.at("l_d").get<double>() > 0.0);  // hinge: 2 at a blind discriminator
    CHECK(std::isfinite(k.at("l_con").get<double>()));
    // Early on the field predicts drops (return probability ≤ 0.5) nearly everywhere: no points.
    CHECK(k.at("coverage").get<double>() >= 0.0);
    CHECK(k.at("coverage").get<double>() <= 1.0);
    CHECK((k.at("coverage").get<double>() > 0.0) == (k.at("rendered_points").get<int>() > 0));
    with_points += k.at("rendered_points").get<int>() > 0;
    CHECK(std::isfinite(k.at("d_real").get<double>()));
    CHECK(std::isfinite(k.at("d_fake").get<double>()));
    const int i = k.at("pair")[0].get<int>(), jj = k.at("pair")[1].get<int>();
    CHECK(std::abs(i - jj) == 1);
    CHECK(i != 13);
    CHECK(jj != 13);
  }
  CHECK(logged >= 3);
  CHECK(with_points >= 1);
  // The term reached the field: without it the same run ends elsewhere.
  {
    const TrainRequest req =
        test::tiny_request("sg-nlf", data, tiny_sgnlf(Json{{"consistency", nullptr}}),
                           test::temp_dir("consistency_off"), 3);
    const Json off = train_run(test::runtime(), req);
    CHECK_FALSE(off.contains("consistency_steps"));
    LoadedRun a = load_run(test::runtime(), full), b = load_run(test::runtime(), req.run_dir);
    CHECK(a.model->params() != b.model->params());
  }

  // Killed before step 6 (pose gradients of frame j pending; the resumed run's first step is a
  // consistency step with rendered points, under the coarse-to-fine mask of its own step) and
  // resumed: bit-identical field, discriminator and poses.
  const std::string part = test::temp_dir("consistency_part");
  run(part, 6, false);
  run(part, -1, true);
  const Checkpoint ca = load_latest_checkpoint(checkpoint_path(full), tiny_sgnlf().hash(), 3);
  const Checkpoint cb = load_latest_checkpoint(checkpoint_path(part), tiny_sgnlf().hash(), 3);
  for (const char* name : {"params", "adam_m", "consistency.disc.params", "consistency.disc.adam_m",
                           "consistency.disc.adam_v", "consistency.disc.adam_t",
                           "consistency.pose_pending", "poses.xi", "poses.adam_m"}) {
    INFO(name);
    // Bitwise: doubles packed into float slots (pack_doubles) may read as float NaNs.
    const auto& xa = ca.array(name);
    const auto& xb = cb.array(name);
    REQUIRE(xa.size() == xb.size());
    CHECK(std::memcmp(xa.data(), xb.data(), xa.size() * sizeof(float)) == 0);
  }
  LoadedRun a = load_run(test::runtime(), full), b = load_run(test::runtime(), part);
  CHECK(a.model->params() == b.model->params());
  for (size_t i = 0; i < a.T_world_lidar.size(); ++i)
    CHECK(a.T_world_lidar[i].matrix() == b.T_world_lidar[i].matrix());
  // The discriminator trained: its parameters moved from the initial ones.
  const adversarial::PatchDiscriminator d0(test::runtime(), tiny_sgnlf().consistency->discriminator);
  CHECK(ca.array("consistency.disc.params") != d0.initial_params());
}

TEST_CASE("consistency config: validated section, unknown keys rejected, ablation unchanged",
          "[pipeline][consistency]") {
  CHECK(tiny_sgnlf().consistency_term());
  CHECK_FALSE(tiny_sgnlf(Json{{"consistency", nullptr}}).consistency_term());
  CHECK_THROWS_WITH(tiny_sgnlf(Json{{"consistency", {{"enabled", false}}}}),
                    Catch::Contains("'enabled' is not a key"));
  CHECK_THROWS_WITH(tiny_sgnlf(Json{{"consistency", {{"bogus", 1}}}}), Catch::Contains("bogus"));
  CHECK_THROWS_WITH(tiny_sgnlf(Json{{"consistency", {{"every", 0}}}}), Catch::Contains("every"));
  CHECK_THROWS_WITH(tiny_sgnlf(Json{{"consistency", {{"weight", -1.0}}}}), Catch::Contains("weight"));
  CHECK_THROWS_WITH(tiny_sgnlf(Json{{"consistency", {{"offsets", Json::array()}}}}),
                    Catch::Contains("offsets"));
  CHECK_THROWS_WITH(tiny_sgnlf(Json{{"consistency", {{"offsets", {0}}}}}), Catch::Contains("offsets[0]"));
  CHECK_THROWS_WITH(tiny_sgnlf(Json{{"consistency", {{"return_threshold", 1.5}}}}),
                    Catch::Contains("return_threshold"));
  CHECK_THROWS_WITH(tiny_sgnlf(Json{{"consistency", {{"render_cols", 4}}}}),
                    Catch::Contains("render_cols"));
  // The render grid is one forward: at most the model's ray capacity (512 here).
  CHECK_THROWS_WITH(tiny_sgnlf(Json{{"consistency", {{"render_rows", 16}, {"render_cols", 64}}}}),
                    Catch::Contains("capacity"));
  CHECK_THROWS_WITH(tiny_sgnlf(Json{{"consistency", {{"discriminator", {{"bogus", 1}}}}}}),
                    Catch::Contains("bogus"));
  CHECK_THROWS_WITH(tiny_sgnlf(Json{{"consistency", {{"discriminator", {{"scales", 5}}}}}}),
                    Catch::Contains("scales"));
  // Sizes that depend on the dataset's sensor (16 × 128) fail when the term is built.
  const Scene scene = make_scene(test::tiny_dataset());
  auto build = [&](const Json& extra) {
    return ConsistencyTerm(test::runtime(), scene, *tiny_sgnlf(extra).consistency, 512);
  };
  // A stride that does not divide the sensor is fitted to the nearest divisor (any folder's
  // sensor runs, e.g. 2004 columns); one beyond the sensor's size is refused by name.
  CHECK(fitted_stride(128, 3) == 4);
  CHECK(fitted_stride(2004, 10) == 12);
  CHECK(fitted_stride(2004, 6) == 6);
  CHECK(fitted_stride(67, 10) == 1);  // a prime: only 1 (and 67) divide it
  const auto fitted = fit_consistency_to_sensor(
      *tiny_sgnlf(Json{{"consistency", {{"image_col_stride", 3}}}}).consistency, scene.sensor);
  CHECK(fitted.image_col_stride == 4);
  CHECK(consistency_image_sensor(fitted, scene.sensor).width == 32);
  CHECK_NOTHROW(build(Json{{"consistency", {{"image_col_stride", 3}}}}));
  CHECK_THROWS_WITH(build(Json{{"consistency", {{"image_row_stride", 32}}}}),
                    Catch::Contains("image_row_stride"));
  // The discriminator is fitted to the image sub-sensor (16 × 128 / strides): three scales
  // would leave the third none, so it runs with the scales that fit.
  const auto three = *tiny_sgnlf(Json{{"consistency", {{"discriminator", {{"scales", 3}}}}}}).consistency;
  CHECK(fit_consistency_to_sensor(three, scene.sensor).discriminator.scales < 3);
  CHECK_NOTHROW(build(Json{{"consistency", {{"discriminator", {{"scales", 3}}}}}}));
  // The ablation has no section at all: its config (and hash) are what they were.
  const TrainConfig ab = resolve_config("sg-nlf-no-consistency", "smoke", Json::object());
  CHECK_FALSE(ab.consistency_term());
  CHECK_FALSE(train_config_to_json(ab).contains("consistency"));
  CHECK_THROWS_WITH(resolve_config("sg-nlf-no-consistency", "smoke",
                                   Json{{"consistency", {{"every", 1}}}}),
                    Catch::Contains("consistency"));
  // Every preset of sg-nlf resolves with the term on, and its sub-sensors and discriminator
  // fit both sensors (the smoke tables simulate them 256 columns wide) and the sensors plain
  // folders yield: a KITTI HDL-64E estimate with merged beams (61 × 2 004, 59 rows: primes),
  // a 16-beam head, a prime width.
  for (const char* scale : {"smoke", "quick", "paper"}) {
    const TrainConfig pc = resolve_config("sg-nlf", scale, Json::object());
    CHECK(pc.consistency_term());
    for (const std::string sensor : {"kitti360", "nuscenes", "61x2004", "59x2010", "16x900", "32x1087"}) {
      INFO(scale << " " << sensor);
      Scene sc;
      if (sensor == "kitti360" || sensor == "nuscenes") {
        sc.sensor = sensor_preset(sensor);
      } else {
        sc.sensor = sensor_preset("kitti360");
        sc.sensor.name = "estimated";
        sc.sensor.height = std::stoi(sensor.substr(0, sensor.find('x')));
        sc.sensor.width = std::stoi(sensor.substr(sensor.find('x') + 1));
      }
      if (std::string(scale) == "smoke" && (sensor == "kitti360" || sensor == "nuscenes")) sc.sensor.width = 256;
      sc.norm.scale = 0.01;
      sc.images.assign(2, RangeImage(sc.sensor.height, sc.sensor.width));
      CHECK_NOTHROW(ConsistencyTerm(test::runtime(), sc, *pc.consistency,
                                    std::max(pc.schedule.rays_per_batch,
                                             pc.schedule.render_chunk_rays)));
    }
  }
}
