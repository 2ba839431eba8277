// Training with the surface sampler (render::SurfaceSampler) and weight carving: the run trains,
// logs its carving term and is deterministic; the head's parameter gradient against finite
// differences with and without surface sampling.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/config.hpp"
#include "field/mlp.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "pipeline/train/trainer.hpp"
#include "support/test_device.hpp"
#include "render_fixtures.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::pipeline;

TEST_CASE("surface sampling with weight carving trains, logs its term and is deterministic",
          "[pipeline][train][device]") {
  const Dataset& d = test::tiny_dataset();
  const Scene scene = make_scene(d);
  const TrainConfig c = test::tiny_config(Json{
      {"schedule", {{"iterations", 120}, {"checkpoint_every", 0}, {"log_every", 1}}},
      {"render", {{"surface_band_samples", 8}, {"surface_free_samples", 8},
                  {"surface_behind_samples", 2}, {"surface_anneal_steps", 60},
                  {"weights", {{"carve", 10.0}}}}}});
  REQUIRE(c.render.surface_sampling());
  // 18 samples per training ray: more than the 16 + 4 of the protocol's sampling is not needed.
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), 512);
  TrainOptions opt;
  opt.run_dir = test::temp_dir("surface_train");
  opt.seed = 3;
  opt.show_progress = false;
  CHECK(train(model, scene, c, opt).finished);
  std::vector<double> losses, carve;
  std::ifstream in(opt.run_dir + "/train_log.jsonl");
  for (std::string line; std::getline(in, line);) {
    const Json j = Json::parse(line);
    losses.push_back(j["loss"]["total"]);
    carve.push_back(j["loss"].value("carve", 0.0));
  }
  REQUIRE(losses.size() == 120);
  double first = 0, last = 0, carve_first = 0;
  for (int i = 0; i < 12; ++i) {
    first += losses[size_t(i)];
    last += losses[losses.size() - 1 - size_t(i)];
    carve_first += carve[size_t(i)];
  }
  INFO("first " << first / 12 << " last " << last / 12 << " carve " << carve_first / 12);
  CHECK(carve_first > 0.0);  // the term is on and logged
  CHECK(last < 0.5 * first);
  const RangeImage img = render_view(model, scene, d.frames[13].T_world_lidar, 512);
  for (float v : img.range) REQUIRE(std::isfinite(v));
  // Same seed: bit-identical parameters.
  LidarNerfModel again(test::runtime(), c, float(scene.norm.scale), 512);
  opt.run_dir = test::temp_dir("surface_train_b");
  train(again, scene, c, opt);
  CHECK(again.params() == model.params());
}

TEST_CASE("surface sampling: the head's parameter gradient matches finite differences",
          "[pipeline][train][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  for (const bool surface : {false, true}) {
    Json render{{"weights", {{"depth", 0.0}, {"ret", 1.0}, {"intensity", 1.0}, {"grad", 0.0}}}};
    if (surface)
      render.update(Json{{"surface_band_samples", 8}, {"surface_free_samples", 8},
                         {"surface_behind_samples", 2}});
    const TrainConfig c = test::tiny_config(Json{{"render", render}});
    LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), 512);
    model.init_params(5);
    const RayBatch b = draw_ray_batch(scene, c, 5, 1);  // a pixel batch (odd epoch)
    REQUIRE_FALSE(b.patches);
    model.forward_backward(b, 9, 1);
    const double l0 = double(model.read_losses().total());
    const auto g = model.read_gradient();
    const std::vector<float> st = model.params();
    const field::ParamSlice head = model.layout().slice("head_mlp");
    // Central differences in float: a step that crosses a ReLU kink of the head spoils its
    // element, so most elements must agree closely and none may be far off (a wrong or missing
    // term spoils them all).
    std::vector<double> rel;
    for (size_t k = head.offset; k < head.offset + head.count; k += head.count / 41) {
      const double eps = 3e-3;
      std::vector<float> p = st;
      p[k] += float(eps);
      model.set_params(p);
      model.forward_backward(b, 9, 1);
      const double lp = double(model.read_losses().total());
      p[k] -= float(2 * eps);
      model.set_params(p);
      model.forward_backward(b, 9, 1);
      const double lm = double(model.read_losses().total());
      const double fd = (lp - lm) / (2 * eps);
      rel.push_back(std::abs(fd - g[k]) / (1e-3 + std::abs(fd)));
    }
    std::sort(rel.begin(), rel.end());
    INFO("surface " << surface << " loss " << l0 << " relative errors: median "
                    << rel[rel.size() / 2] << ", 90th percentile " << rel[rel.size() * 9 / 10]
                    << ", worst " << rel.back());
    REQUIRE(rel.size() > 35);
    CHECK(rel[rel.size() * 9 / 10] < 0.02);
    CHECK(rel.back() < 0.25);
  }
}
