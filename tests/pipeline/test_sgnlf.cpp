// SG-NLF's hybrid field in the pipeline (issue "SG-NLF, part 1", item 1): the gradient of one
// whole training step with respect to ξ through [f_geo, λ·Ψ] against finite differences; a run
// folder of the hybrid method (Ψ trained on the current surface, λ ramp, exact resume including
// Ψ and the surface pool, evaluation restoring Ψ); the "spectral" config section's validation;
// the step parts' schedules independent of their composition order.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/config.hpp"
#include "pipeline/train/checkpoint.hpp"
#include "pipeline/methods/registry.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "pipeline/run/run_dir.hpp"
#include "pipeline/run/session.hpp"
#include "pipeline/train/step_parts.hpp"
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

const char* kMethod = "sg-nlf-no-consistency";

TrainConfig tiny_hybrid(const Json& extra = Json::object()) {
  return resolve_config(kMethod, "smoke",
                        merge_config_json(test::tiny_sgnlf_overrides(false), extra));
}

}  // namespace

TEST_CASE("hybrid field: analytic dL/dxi of one training step matches finite differences",
          "[pipeline][sgnlf][device]") {
  const Dataset& d = test::tiny_dataset();
  TrainConfig c = tiny_hybrid(Json{{"render", {{"n_samples", 48}}}, {"schedule", {{"iterations", 40}}}});
  const Scene scene = make_scene(d);
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), 512);
  model.set_fusion_weight(1.0f);  // Ψ fully fused: its share of dL/dx must be in the gradient
  TrainOptions opt;
  opt.run_dir = test::temp_dir("sgnlf_fd");
  opt.show_progress = false;
  opt.resume = false;
  train(model, scene, c, opt);
  Vec6 xi0;
  xi0 << 0.01, -0.02, 0.015, 0.004, -0.003, 0.002;
  // eps smaller than the hash-grid test's 5e-5: the trained hybrid state has a ~14× smaller
  // gradient here, so cell crossings of the piecewise-trilinear grid weigh more (measured:
  // 5e-5 puts one component 6.5 % of the largest off, 2e-5 all within 1.6 %).
  test::check_pose_step_gradients(test::pose_step_gradients(model, scene, c, 41, xi0, 2e-5));
}

TEST_CASE("hybrid field run folder: spectral schedule, exact resume, evaluation restores Psi",
          "[pipeline][sgnlf][session][device]") {
  const std::string data = test::temp_dir("sgnlf_data") + "/seq";
  test::write_tiny_dataset(data);
  auto run = [&](const std::string& dir, long stop_at, bool resume) {
    return train_run(test::runtime(),
                     test::tiny_request(kMethod, data, tiny_hybrid(), dir, 3, stop_at, resume));
  };
  const std::string full = test::temp_dir("sgnlf_full");
  const Json s = run(full, -1, false);
  CHECK(s.at("finished").get<bool>());
  CHECK(s.at("spectral_seconds").get<double>() > 0.0);
  // The log carries the spectral loss (a loss term's value, out of the total), λ and the pool
  // size; λ ramps 0 → 1 over steps 4..14.
  std::ifstream log(full + "/train_log.jsonl");
  std::string line;
  std::vector<double> lambdas, losses;
  while (std::getline(log, line)) {
    const Json j = Json::parse(line);
    if (!j.contains("lambda")) continue;
    lambdas.push_back(j.at("lambda").get<double>());
    losses.push_back(j.at("loss").at("spectral").get<double>());
    CHECK(j.at("surface_points").get<int>() > 100);
  }
  REQUIRE(lambdas.size() >= 3);
  CHECK(lambdas.front() < 1.0);
  CHECK(lambdas.back() == 1.0);
  for (double l : losses) CHECK(std::isfinite(l));

  // The confidence-aware pose graph from epoch 1 on (epochs of 14 steps here): its files, the
  // geometric log's record of it, and `eval`'s count of its non-adjacent edges.
  CHECK(fs::exists(full + "/pose_graph/epoch_00001.json"));
  CHECK(fs::exists(full + "/pose_graph/epoch_00001.svg"));
  const Json g1 = load_json_file(full + "/pose_graph/latest.json");
  CHECK(g1.at("edges").size() > 0);
  bool logged = false;
  int build_runs = 0;
  std::ifstream glog(full + "/geometric_log.jsonl");
  while (std::getline(glog, line)) {
    const Json j = Json::parse(line);
    if (!j.contains("pose_graph")) continue;
    logged = true;
    // Each build settles the poses on the new graph: steps_on_build 6 shrunk by progress.
    if (j.at("pose_graph").contains("build_run")) {
      const Json& b = j.at("pose_graph").at("build_run");
      CHECK(b.at("steps").get<int>() >= 1);
      CHECK(b.at("steps").get<int>() <= 6);
      ++build_runs;
    }
  }
  CHECK(logged);
  CHECK(build_runs >= 1);

  // Killed after step 20 (after the graph was built, λ at 1) and resumed: bit-identical field,
  // Ψ, pose graph and poses.
  const std::string part = test::temp_dir("sgnlf_part");
  run(part, 20, false);
  run(part, -1, true);
  LoadedRun a = load_run(test::runtime(), full), b = load_run(test::runtime(), part);
  CHECK(a.model->params() == b.model->params());
  CHECK(a.model->read_psi() == b.model->read_psi());
  // Ψ's optimiser (the spectral loss term's) resumed too: the checkpoints' moments agree.
  const Checkpoint cka = load_checkpoint(full + "/checkpoints/latest.ckpt"),
                   ckb = load_checkpoint(part + "/checkpoints/latest.ckpt");
  CHECK(cka.array("spectral.psi.adam_m") == ckb.array("spectral.psi.adam_m"));
  CHECK(cka.array("spectral.psi.adam_t") == ckb.array("spectral.psi.adam_t"));
  CHECK(a.model->fusion_weight() == 1.0f);
  for (size_t i = 0; i < a.T_world_lidar.size(); ++i)
    CHECK(a.T_world_lidar[i].matrix() == b.T_world_lidar[i].matrix());
  // Evaluation from the folder renders with the trained Ψ and λ (restored from the checkpoint):
  // both folders give the same metrics, and switching Ψ off changes them.
  const Json ea = eval_run(a, full);
  CHECK(ea.at("pose_graph").at("non_adjacent_edges").get<long>() ==
        g1.at("non_adjacent_edges").get<long>());
  CHECK(load_json_file(part + "/pose_graph/latest.json").at("edges") == g1.at("edges"));
  const double rmse = ea.at("metrics").at("depth_rmse").get<double>();
  CHECK(eval_run(b, part).at("metrics").at("depth_rmse").get<double>() == rmse);
  a.model->set_fusion_weight(0.0f);
  CHECK(eval_run(a, full).at("metrics").at("depth_rmse").get<double>() != rmse);
}

TEST_CASE("hybrid field config: validated section, unknown keys rejected",
          "[pipeline][sgnlf]") {
  CHECK(tiny_hybrid().hybrid_encoder());
  // The section's presence is its switch: taken out, the plain hash grid; an "enabled" key is
  // refused with what to do instead.
  CHECK_FALSE(tiny_hybrid(Json{{"spectral", nullptr}}).hybrid_encoder());
  CHECK_THROWS_WITH(tiny_hybrid(Json{{"spectral", {{"enabled", false}}}}),
                    Catch::Contains(".spectral: 'enabled' is not a key") &&
                        Catch::Contains("remove the section"));
  CHECK_THROWS_WITH(tiny_hybrid(Json{{"pose_graph", {{"enabled", true}}}}),
                    Catch::Contains(".pose_graph: 'enabled' is not a key"));
  CHECK_THROWS_WITH(tiny_hybrid(Json{{"spectral", {{"bogus", 1}}}}), Catch::Contains("bogus"));
  CHECK_THROWS_WITH(tiny_hybrid(Json{{"spectral", {{"every", 0}}}}), Catch::Contains("every"));
  CHECK_THROWS_WITH(tiny_hybrid(Json{{"spectral", {{"psi", {{"k", 0}}}}}}), Catch::Contains("k"));
  CHECK_THROWS_WITH(tiny_hybrid(Json{{"pose_graph", {{"steps_on_build", -1}}}}),
                    Catch::Contains("steps_on_build"));
  CHECK_THROWS_WITH(tiny_hybrid(Json{{"pose_graph", {{"lr_on_build", 0.0}}}}),
                    Catch::Contains("lr_on_build"));
  CHECK_THROWS_WITH(tiny_hybrid(Json{{"pose_graph", {{"bogus", 1}}}}), Catch::Contains("bogus"));
  // A method without the hybrid field has no "spectral" section.
  CHECK_THROWS_WITH(resolve_config("geonlf", "smoke", Json{{"spectral", {{"every", 1}}}}),
                    Catch::Contains("spectral"));
  // sg-nlf itself is trainable since its adversarial term exists (test_consistency.cpp); the
  // ablation without it keeps the config it had.
  CHECK(resolve_config("sg-nlf", "smoke", Json::object()).consistency_term());
  CHECK_FALSE(tiny_hybrid().consistency.has_value());
}

TEST_CASE("the step's schedules do not depend on the order the step parts are composed in",
          "[pipeline][sgnlf][device]") {
  // SG-NLF composes spectral(consistency(pose_free)): the trainer sets every part's schedule
  // (λ(t), the coarse-to-fine mask) before the step runs, so the consistency term renders with
  // the step's λ whichever part wraps the other. The two orders give the same field bits.
  const Dataset& d = test::tiny_dataset();
  const TrainConfig c = resolve_config("sg-nlf", "smoke", test::tiny_sgnlf_overrides(true));
  REQUIRE(c.consistency_term());
  const RunScene rs = make_run_scene(d, c);
  auto run = [&](bool spectral_outside) {
    LidarNerfModel model(test::runtime(), c, float(rs.scene.norm.scale), model_capacity(c));
    model.init_params(1);
    RunStepParts parts(test::runtime(), d, rs.scene, c, model,
                       test::temp_dir(spectral_outside ? "sched_a" : "sched_b"), 1);
    StepPolicy& policy = spectral_outside ? parts.spectral(parts.consistency(parts.pose_free()))
                                          : parts.consistency(parts.spectral(parts.pose_free()));
    policy.on_epoch(0, 0);
    FieldOptimizer optim(model, c);
    std::vector<float> lambdas;
    for (long s = 0; s < 12; ++s) {  // λ ramps over steps 4..14; consistency from step 4
      policy.set_schedules(model, s);
      lambdas.push_back(model.fusion_weight());
      policy.step(model, optim, 1, s, 1e-2f);
    }
    CHECK(lambdas.front() == 0.0f);
    CHECK(lambdas.back() == float(c.spectral->fusion.lambda(11)));
    CHECK(lambdas.back() > 0.0f);
    return model.params();
  };
  CHECK(run(true) == run(false));
}
