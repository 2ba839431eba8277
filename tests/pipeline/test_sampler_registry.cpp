// The sampler registry (pipeline/model/sampler.hpp) and docs/architecture.md's recipe "A
// sampler": two strategies registered from this file alone, selected by name in the config,
// placing the samples the model's one forward path runs on. "toy_uniform" is the built-in
// uniform strategy written again on a launcher of its own (the same bits as "uniform");
// "toy_dense" places 3 × n_samples samples per ray, more than any built-in strategy under the
// same config, so the model's buffers follow its per_ray. Also the names the numeric keys imply
// (configs without the keys keep their JSON), and the errors naming the key.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "core/config.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "support/test_device.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {

// Stratified samples from a RaySampler of its own over the render config with `factor` ×
// n_samples, clamped to the scene box; every sample evaluated by the field.
class ToySampler final : public Sampler {
 public:
  ToySampler(const SamplerContext& c, int factor)
      : rays_(c.rt, with_samples(c.render, factor * c.render.n_samples), c.scene_scale),
        buf_(c.buffers), clamp_(c.field.clamp) {}
  SampleSet sample(const SampleRequest& r) override {
    rays_.uniform(buf_.origins, buf_.directions, r.n_rays, r.jitter, r.seed, r.step, buf_.t,
                  buf_.x);
    const int M = rays_.uniform_samples();
    clamp_(buf_.x, r.n_rays * M);
    SampleSet s;
    s.n_rays = r.n_rays, s.per_ray = M, s.rows = s.samples();
    return s;
  }

 private:
  static render::RenderConfig with_samples(render::RenderConfig rc, int n) {
    rc.n_samples = n;
    return rc;
  }
  render::RaySampler rays_;
  SampleBuffers buf_;
  std::function<void(cl::Buffer&, int)> clamp_;
};

std::unique_ptr<Sampler> make_toy_uniform(const SamplerContext& c) {
  return std::make_unique<ToySampler>(c, 1);
}
std::unique_ptr<Sampler> make_toy_dense(const SamplerContext& c) {
  return std::make_unique<ToySampler>(c, 3);
}

// The recipe: a name, the samples per ray under a render config, no check, the factory.
const SamplerRegistration toy_uniform{SamplerKind{
    "toy_uniform", [](const render::RenderConfig& rc) { return rc.n_samples; }, nullptr,
    make_toy_uniform}};
const SamplerRegistration toy_dense{SamplerKind{
    "toy_dense", [](const render::RenderConfig& rc) { return 3 * rc.n_samples; }, nullptr,
    make_toy_dense}};

std::unique_ptr<LidarNerfModel> model_of(const Scene& scene, const TrainConfig& c) {
  auto m = std::make_unique<LidarNerfModel>(test::runtime(), c, float(scene.norm.scale), 512);
  m->init_params(5);
  return m;
}

}  // namespace

TEST_CASE("the sampler names: the registry's, and those the numeric keys imply",
          "[pipeline][sampler]") {
  const std::vector<std::string> names = sampler_names();
  for (const char* n : {"uniform", "importance", "terminated", "surface", "toy_uniform"})
    CHECK(std::find(names.begin(), names.end(), n) != names.end());
  CHECK(std::is_sorted(names.begin(), names.end()));
  CHECK_THROWS_WITH(
      register_sampler(SamplerKind{
          "uniform", [](const render::RenderConfig&) { return 1; }, nullptr, make_toy_dense}),
      Catch::Contains("registered already"));

  render::RenderConfig rc;
  rc.n_importance = 0;
  CHECK(rc.sampler_name() == "uniform");
  rc.n_importance = 8;
  CHECK(rc.sampler_name() == "importance");
  CHECK(rc.training_sampler_name() == "importance");
  rc.stop_transmittance = 0.01f;
  CHECK(rc.sampler_name() == "terminated");
  rc.surface_band_samples = 4;
  CHECK(rc.training_sampler_name() == "surface");
  CHECK(rc.sampler_name() == "terminated");
  // Absent keys are not written: the configs before them keep their JSON and hash.
  const Json j = rc.to_json();
  CHECK_FALSE(j.contains("sampler"));
  CHECK_FALSE(j.contains("training_sampler"));
  // Named, they win over the numeric keys and are written.
  rc.sampler = "toy_uniform", rc.training_sampler = "uniform";
  CHECK(rc.sampler_name() == "toy_uniform");
  CHECK(rc.training_sampler_name() == "uniform");
  CHECK(rc.to_json().at("sampler") == "toy_uniform");
  CHECK(render::RenderConfig::from_json(rc.to_json(), "render").training_sampler == "uniform");
}

TEST_CASE("a sampler registered from a test is selected by name and runs the forward path",
          "[pipeline][sampler][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const int S = 16;  // tiny_config's n_samples
  const Json uniform{{"render", {{"n_importance", 0}}}};
  SECTION("toy_uniform for every pass: the built-in uniform's bits") {
    const TrainConfig a = test::tiny_config(uniform);
    const TrainConfig b =
        test::tiny_config(Json{{"render", {{"n_importance", 0}, {"sampler", "toy_uniform"}}}});
    auto ma = model_of(scene, a), mb = model_of(scene, b);
    CHECK(ma->protocol_strategy() == "uniform");
    CHECK(mb->protocol_strategy() == "toy_uniform");
    CHECK(mb->training_strategy() == "toy_uniform");
    const RayBatch batch = draw_ray_batch(scene, a, 5, 14);
    ma->forward_backward(batch, 9, 14);
    mb->forward_backward(batch, 9, 14);
    CHECK(mb->last_forward().samples.strategy == "toy_uniform");
    CHECK(mb->last_forward().samples.per_ray == S);
    CHECK(ma->read_gradient() == mb->read_gradient());
    CHECK(ma->render_rays(batch.origins, batch.directions, batch.n_rays) ==
          mb->render_rays(batch.origins, batch.directions, batch.n_rays));
  }
  SECTION("toy_dense for training rays: the buffers hold its samples, rendering keeps the "
          "protocol's") {
    const TrainConfig c = test::tiny_config(Json{{"render", {{"training_sampler", "toy_dense"}}}});
    auto m = model_of(scene, c);
    CHECK(m->training_strategy() == "toy_dense");
    CHECK(m->protocol_strategy() == "importance");
    const RayBatch batch = draw_ray_batch(scene, c, 5, 14);
    m->forward_backward(batch, 9, 14);
    const ForwardContext ctx = m->last_forward();
    CHECK(ctx.samples.strategy == "toy_dense");
    CHECK(ctx.samples.per_ray == 3 * S);
    CHECK(ctx.samples.rows == long(batch.n_rays) * 3 * S);
    CHECK(ctx.head_rows == ctx.samples.rows);
    const std::vector<float> g = m->read_gradient();
    size_t nonzero = 0;
    bool finite = true;
    for (const float v : g) nonzero += v != 0.0f, finite = finite && std::isfinite(v);
    CHECK(finite);
    CHECK(nonzero > 100);
    const auto out = m->render_rays(batch.origins, batch.directions, batch.n_rays);
    CHECK(m->last_forward().samples.strategy == "importance");
    CHECK(out.size() == size_t(batch.n_rays) * 3);
  }
  SECTION("an unknown name, or a strategy the config cannot run: ConfigError naming the key") {
    CHECK_THROWS_WITH(model_of(scene, test::tiny_config(Json{{"render", {{"sampler", "nope"}}}})),
                      Catch::Contains("render.sampler: unknown sampler 'nope'") &&
                          Catch::Contains("toy_uniform"));
    CHECK_THROWS_AS(
        model_of(scene, test::tiny_config(Json{{"render", {{"training_sampler", "nope"}}}})),
        ConfigError);
    CHECK_THROWS_WITH(
        model_of(scene, test::tiny_config(merge_config_json(
                            uniform, Json{{"render", {{"sampler", "importance"}}}}))),
        Catch::Contains("render.sampler: the 'importance' sampler needs render.n_importance > 0"));
    CHECK_THROWS_WITH(
        model_of(scene, test::tiny_config(Json{{"render", {{"training_sampler", "surface"}}}})),
        Catch::Contains("render.training_sampler") && Catch::Contains("surface_band_samples"));
    CHECK_THROWS_WITH(
        model_of(scene, test::tiny_config(Json{{"render", {{"sampler", "terminated"}}}})),
        Catch::Contains("stop_transmittance"));
  }
}
