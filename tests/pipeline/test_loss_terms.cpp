// The list of loss terms (pipeline/model/loss_term.hpp) open to a term registered from a test:
// a term with a pass of its own through the field (as the cross-frame consistency) and a term on
// the batch's output gradient take part in the model's step; their gradient joins the batch's
// one Adam step, their values reach the step's LossReport and the training log; a pass's rays
// are differentiated only while their activations are theirs, and one term writes the second
// gradient per step; a term with a parameter group of its own (as SG-NLF's spectral Ψ) takes its
// own optimiser's step after the batch's backward, without touching the field's gradient.
#include <catch2/catch.hpp>

#include <algorithm>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "field/adam.hpp"
#include "core/config.hpp"
#include "core/rng.hpp"
#include "pipeline/model/loss_term.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "pipeline/train/trainer.hpp"
#include "spectral/surface.hpp"
#include "support/test_device.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {

constexpr int kRays = 200;

// Renders 200 rays of frame 2 at its pose in its own pass and sends a fixed per-ray depth
// gradient back; reports its "value" (the sum of the gradients it sent, out of the total).
class ToyRenderTerm final : public LossTerm {
 public:
  ToyRenderTerm(const Scene& scene, int mode = 0) : mode_(mode) {
    image_rays(scene, scene.T_world_lidar[2], 0, kRays, o_, d_);
    g_.assign(size_t(kRays) * 3, 0.0f);
    for (int k = 0; k < kRays; ++k) g_[3 * size_t(k)] = (k % 3 == 0 ? 1.0f : -0.5f) * 1e-2f;
  }
  const char* name() const override { return "toy_render"; }
  void add_field_gradient(FieldPass& field) override {
    ++runs;
    const RenderedRays rays = field.render(o_, d_, kRays);
    if (mode_ == 1) field.render(o_, d_, kRays);  // a second pass overwrites the first's
    field.backward(rays, g_, false);
    if (mode_ == 2) field.backward(rays, g_, false);  // the second gradient written twice
  }
  void report(LossReport& r, const std::vector<float>&) const override {
    r.add("toy_render", 0.25 * runs, false);
  }
  int runs = 0;

 private:
  int mode_;
  std::vector<float> o_, d_, g_;
};

// Adds a constant to every ray's depth gradient of the batch; reports "toy" in the total.
class ToyOutputTerm final : public LossTerm {
 public:
  const char* name() const override { return "toy"; }
  void add_output_gradient(LossPass& p) override {
    std::vector<float> g = p.grad_out.read_vec<float>(size_t(p.n_rays) * 3);
    for (int i = 0; i < p.n_rays; ++i) g[3 * size_t(i)] += 1e-3f;
    p.grad_out.write_vec(g);
  }
  void report(LossReport& r, const std::vector<float>&) const override { r.add("toy", 0.5); }
};

// Takes one step of its own Adam over Ψ at every even step on a batch of a sphere's surface
// samples; reports the last spectral loss, out of the total.
class ToyGroupTerm final : public LossTerm {
 public:
  explicit ToyGroupTerm(size_t psi_params) : adam(test::runtime(), std::max<size_t>(psi_params, 1)) {
    const auto shape =
        spectral::make_shape(spectral::ShapeSpec::preset(spectral::ShapeKind::sphere));
    Rng rng(3, 1);
    batch_ = shape->sample(rng, 64);
  }
  const char* name() const override { return "toy_group"; }
  void take_own_step(OwnGroupStep& group) override {
    steps.push_back(group.step);
    if (group.step % 2 != 0) return;
    last = group.spectral_gradient(batch_);
    const OwnGroupStep::Group psi = group.psi();
    adam.begin_step();
    adam.update(psi.params, psi.grad, 0, psi.count, 1e-2f);
  }
  void report(LossReport& r, const std::vector<float>&) const override {
    r.add("toy_group", last, false);
  }
  std::vector<long> steps;
  double last = 0.0;
  field::Adam adam;

 private:
  std::vector<spectral::SurfacePoint> batch_;
};

std::unique_ptr<LidarNerfModel> fresh(const Scene& scene, const TrainConfig& c) {
  auto m = std::make_unique<LidarNerfModel>(test::runtime(), c, float(scene.norm.scale), 512);
  m->init_params(5);
  return m;
}

}  // namespace

TEST_CASE("a loss term with its own pass: its gradient joins the batch's Adam step",
          "[pipeline][loss_terms][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = test::tiny_config();
  const float lr = 1e-2f;
  const RayBatch b = draw_ray_batch(scene, c, 7, 3);

  auto plain = fresh(scene, c);
  plain->forward_backward(b, 7, 3);
  const auto g_batch = plain->read_gradient();
  auto m = fresh(scene, c);
  auto& toy = static_cast<ToyRenderTerm&>(m->add_loss(std::make_unique<ToyRenderTerm>(scene)));
  CHECK(m->loss_names() == std::vector<std::string>{"range", "patch_gradient", "toy_render"});
  const auto p0 = m->params();
  FieldOptimizer optim(*m, c);
  m->forward_backward(b, 7, 3);
  optim.step(lr);
  CHECK(toy.runs == 1);
  const auto g_both = m->read_gradient(), g_own = m->read_term_gradient();
  const auto p1 = m->params();
  REQUIRE(g_both.size() == g_batch.size());
  size_t differ_batch = 0, differ_own = 0, bad = 0, bad_step = 0;
  for (size_t k = 0; k < g_both.size(); ++k) {
    bad += g_both[k] != g_batch[k] + g_own[k];
    differ_batch += g_both[k] != g_batch[k];
    differ_own += g_both[k] != g_own[k];
    // Adam's first step moves each parameter by lr against its gradient's sign (eps 1e-15).
    if (std::abs(g_both[k]) > 1e-10f)
      bad_step += std::abs(p1[k] - p0[k] + lr * (g_both[k] > 0 ? 1.0f : -1.0f)) > 1e-3f * lr;
  }
  CHECK(bad == 0);
  CHECK(bad_step == 0);
  CHECK(differ_batch > 100);  // the term reached the field's parameters …
  CHECK(differ_own > 100);    // … and the batch's loss is still there
  CHECK(optim.steps() == 1);  // one Adam step per training step
  // Its value is reported with the others, out of the total.
  const LossReport r = m->read_losses(), r_plain = plain->read_losses();
  CHECK(r.value("toy_render") == 0.25);
  CHECK(r.total() == r_plain.total());
  CHECK(r.value("depth") == r_plain.value("depth"));

  SECTION("rays whose activations another pass overwrote are not differentiated") {
    auto bad_m = fresh(scene, c);
    bad_m->add_loss(std::make_unique<ToyRenderTerm>(scene, 1));
    CHECK_THROWS_WITH(bad_m->forward_backward(b, 7, 3), Catch::Contains("overwritten"));
  }
  SECTION("one term writes the step's second gradient") {
    auto bad_m = fresh(scene, c);
    bad_m->add_loss(std::make_unique<ToyRenderTerm>(scene, 2));
    CHECK_THROWS_WITH(bad_m->forward_backward(b, 7, 3), Catch::Contains("overwritten"));
    auto two = fresh(scene, c);
    two->add_loss(std::make_unique<ToyRenderTerm>(scene));
    two->add_loss(std::make_unique<ToyRenderTerm>(scene));
    CHECK_THROWS_WITH(two->forward_backward(b, 7, 3), Catch::Contains("another loss term"));
  }
}

TEST_CASE("a loss term on the batch: its output gradient and value take part in training",
          "[pipeline][loss_terms][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = test::tiny_config(Json{{"schedule", {{"iterations", 4}, {"log_every", 2}}}});
  const RayBatch b = draw_ray_batch(scene, c, 7, 3);
  auto plain = fresh(scene, c), m = fresh(scene, c);
  m->add_loss(std::make_unique<ToyOutputTerm>());
  plain->forward_backward(b, 7, 3);
  m->forward_backward(b, 7, 3);
  const auto ga = m->read_output_gradient(), gb = plain->read_output_gradient();
  size_t differ = 0;
  for (size_t i = 0; i < ga.size(); i += 3) differ += ga[i] != gb[i] + 1e-3f;
  CHECK(differ == 0);
  CHECK(m->read_gradient() != plain->read_gradient());
  // In the total, after the batch's terms (float sums in list order).
  const LossReport r = m->read_losses();
  CHECK(r.value("toy") == 0.5);
  CHECK(r.total() == plain->read_losses().total() + 0.5f);

  // A training run logs it beside the config's terms.
  TrainOptions opt;
  opt.run_dir = test::temp_dir("toy_loss_term");
  opt.show_progress = false;
  opt.resume = false;
  const TrainSummary s = train(*m, scene, c, opt);
  CHECK(s.last_loss.value("toy") == 0.5);
  std::ifstream log(std::filesystem::path(opt.run_dir) / "train_log.jsonl");
  std::string line;
  int lines = 0;
  while (std::getline(log, line)) {
    const Json j = Json::parse(line);
    CHECK(j.at("loss").at("toy").get<double>() == 0.5);
    CHECK(j.at("loss").contains("depth"));
    ++lines;
  }
  CHECK(lines >= 2);
}

TEST_CASE("a loss term with its own parameter group: its step follows the batch's backward",
          "[pipeline][loss_terms][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = resolve_config("sg-nlf-no-consistency", "smoke",
                                       test::tiny_sgnlf_overrides(false));
  const RayBatch b = draw_ray_batch(scene, c, 7, 2);
  auto plain = fresh(scene, c), m = fresh(scene, c);
  plain->set_fusion_weight(1.0f);
  m->set_fusion_weight(1.0f);  // Ψ in the field: the batch's forward and backward read it
  auto& toy =
      static_cast<ToyGroupTerm&>(m->add_loss(std::make_unique<ToyGroupTerm>(m->psi_params())));
  const auto psi0 = m->read_psi();
  m->forward_backward(b, 7, 2, true);
  plain->forward_backward(b, 7, 2, true);
  CHECK(toy.steps == std::vector<long>{2});
  // The field's gradient and the rays' gradients are the batch's with Ψ before its step …
  CHECK(m->read_gradient() == plain->read_gradient());
  CHECK(m->read_ray_grads().origin == plain->read_ray_grads().origin);
  // … and Ψ moved by the term's own Adam, one step, outside the field's.
  const auto psi1 = m->read_psi();
  CHECK(psi1 != psi0);
  CHECK(toy.adam.step() == 1);
  FieldOptimizer optim(*m, c);
  optim.step(1e-2f);
  CHECK(optim.steps() == 1);  // the field's optimiser: its own count, Ψ's apart
  CHECK(std::isfinite(toy.last));
  CHECK(toy.last > 0.0);
  CHECK(m->read_losses().value("toy_group") == toy.last);
  CHECK(m->read_losses().total() == plain->read_losses().total());
  // An odd step: the hook runs, the term chooses not to step.
  m->forward_backward(draw_ray_batch(scene, c, 7, 3), 7, 3);
  CHECK(toy.steps == std::vector<long>{2, 3});
  CHECK(m->read_psi() == psi1);

  SECTION("a model without the hybrid field has no such group") {
    auto hg = fresh(scene, test::tiny_config());
    hg->add_loss(std::make_unique<ToyGroupTerm>(1));
    CHECK_THROWS_WITH(hg->forward_backward(b, 7, 2),
                      Catch::Contains("OwnGroupStep::spectral_gradient") &&
                          Catch::Contains("no hybrid spectral-geometric encoder"));
    CHECK_THROWS_WITH(hg->set_fusion_weight(0.5f), Catch::Contains("set_fusion_weight"));
  }
}
