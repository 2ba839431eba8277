// LidarNerfModel's passes (model.hpp): each sampler strategy's sample set (strategy, samples
// per ray, rows, encodings present, live rows, coarse samples) and head rows as the forward's
// context records them; a context whose activations a later pass overwrote is refused; the loss
// terms' list per config, and a term's gradient is exactly its own share of the output
// gradient; the loss read once under the device profile's loss_reduce: device.
#include <catch2/catch.hpp>

#include <numeric>

#include "cl/launch_trace.hpp"
#include "core/config.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "render/chamfer_loss.hpp"
#include "support/test_device.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {

constexpr int kRays = 200;

std::unique_ptr<LidarNerfModel> model_of(const Scene& scene, const TrainConfig& c) {
  auto m = std::make_unique<LidarNerfModel>(test::runtime(), c, float(scene.norm.scale), 512);
  m->init_params(5);
  return m;
}

// The context of rendering kRays rays of frame 2.
ForwardContext render_context(LidarNerfModel& m, const Scene& scene) {
  std::vector<float> o, d;
  image_rays(scene, scene.T_world_lidar[2], 0, kRays, o, d);
  m.render_rays(o, d, kRays);
  return m.last_forward();
}

}  // namespace

TEST_CASE("each sampling strategy's sample set and head rows are in the forward's context",
          "[pipeline][model][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const int S = 16, I = 4;  // tiny_config's
  SECTION("uniform") {
    auto m = model_of(scene, test::tiny_config(Json{{"render", {{"n_importance", 0}}}}));
    CHECK(m->protocol_strategy() == "uniform");
    CHECK_FALSE(m->last_forward().valid());
    const ForwardContext ctx = render_context(*m, scene);
    CHECK(ctx.valid());
    CHECK(ctx.samples.strategy == "uniform");
    CHECK(ctx.samples.per_ray == S);
    CHECK(ctx.samples.rows == long(kRays) * S);
    CHECK_FALSE(ctx.samples.encoded);
    CHECK_FALSE(ctx.samples.compacted);
    CHECK(ctx.samples.coarse == 0);
    CHECK(ctx.head == HeadRows::All);
    CHECK(ctx.head_rows == long(kRays) * S);
    CHECK_THROWS_WITH(m->live_counts(), Catch::Contains("terminate"));
  }
  SECTION("importance, with and without the coarse encodings reused") {
    for (const bool reuse : {true, false}) {
      auto m = model_of(scene, test::tiny_config());
      m->set_reuse_coarse_encodings(reuse);
      CHECK(m->protocol_strategy() == "importance");
      const ForwardContext ctx = render_context(*m, scene);
      CHECK(ctx.samples.strategy == "importance");
      CHECK(ctx.samples.per_ray == S + I);
      CHECK(ctx.samples.rows == long(kRays) * (S + I));
      CHECK(ctx.samples.encoded == reuse);
      CHECK_FALSE(ctx.samples.compacted);
      CHECK(ctx.samples.coarse == long(kRays) * S);
      CHECK(ctx.head == HeadRows::All);
    }
  }
  SECTION("early termination: the live rows, with importance, uniform only, waves, band") {
    const std::vector<Json> renders{
        Json{{"stop_transmittance", 0.01}},
        Json{{"stop_transmittance", 0.01}, {"n_importance", 0}},
        Json{{"stop_transmittance", 0.01}, {"coarse_waves", 4}},
        Json{{"stop_transmittance", 0.01}, {"head_weight_threshold", 1e-3}}};
    for (size_t k = 0; k < renders.size(); ++k) {
      INFO("render " << renders[k].dump());
      auto m = model_of(scene, test::tiny_config(Json{{"render", renders[k]}}));
      CHECK(m->protocol_strategy() == "terminated");
      const ForwardContext ctx = render_context(*m, scene);
      const int M = k == 1 ? S : S + I;
      CHECK(ctx.samples.strategy == "terminated");
      CHECK(ctx.samples.per_ray == M);
      CHECK(ctx.samples.compacted);
      CHECK(ctx.samples.encoded);  // the live rows' encodings, gathered or encoded
      const auto live = m->live_counts();
      REQUIRE(live.size() == size_t(kRays));
      CHECK(ctx.samples.rows == std::accumulate(live.begin(), live.end(), 0L));
      CHECK(ctx.samples.rows <= long(kRays) * M);
      CHECK(ctx.samples.coarse <= long(kRays) * S);
      CHECK(ctx.samples.coarse > 0);
      CHECK(m->live_samples() == ctx.samples.rows);
      CHECK(m->coarse_evaluated() == ctx.samples.coarse);
      if (k == 3) {
        CHECK(ctx.head == HeadRows::Band);
        CHECK(ctx.head_rows <= ctx.samples.rows);
        CHECK(m->head_rows() == ctx.head_rows);
      } else {
        CHECK(ctx.head == HeadRows::Live);
        CHECK(ctx.head_rows == ctx.samples.rows);
        CHECK(m->head_rows() == 0);
      }
      // A pass that overwrites the sample buffers ends the counts' validity.
      m->density_logits(std::vector<float>(30, 0.1f), 10);
      CHECK_THROWS_WITH(m->live_counts(), Catch::Contains("terminate"));
    }
  }
  SECTION("surface: training rays only") {
    const TrainConfig c = test::tiny_config(Json{{"render", {{"surface_band_samples", 8},
                                                             {"surface_free_samples", 8},
                                                             {"surface_behind_samples", 2}}}});
    auto m = model_of(scene, c);
    CHECK(m->training_strategy() == "surface");
    CHECK(m->protocol_strategy() == "importance");
    const RayBatch b = draw_ray_batch(scene, c, 5, 1);
    m->forward_backward(b, 9, 1);
    const ForwardContext ctx = m->last_forward();
    CHECK(ctx.samples.strategy == "surface");
    CHECK(ctx.samples.per_ray == 18);
    CHECK(ctx.samples.rows == long(b.n_rays) * 18);
    CHECK(ctx.samples.coarse == 0);
    CHECK_FALSE(ctx.samples.encoded);
    CHECK(render_context(*m, scene).samples.strategy == "importance");
  }
  SECTION("a training step without surface keys uses the protocol's strategy") {
    const TrainConfig c = test::tiny_config(Json{{"render", {{"stop_transmittance", 0.01}}}});
    auto m = model_of(scene, c);
    CHECK(m->training_strategy() == "terminated");
    m->forward_backward(draw_ray_batch(scene, c, 5, 1), 9, 1);
    CHECK(m->last_forward().samples.strategy == "terminated");
    CHECK(m->last_forward().samples.compacted);
  }
}

TEST_CASE("the loss terms: the list per config, each term's own share of the gradient",
          "[pipeline][model][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  using Names = std::vector<std::string>;
  CHECK(model_of(scene, test::tiny_config())->loss_names() == Names{"range", "patch_gradient"});
  CHECK(model_of(scene, test::tiny_config(Json{{"render", {{"weights", {{"carve", 10.0}}}}}}))
            ->loss_names() == Names{"range", "patch_gradient", "carve"});
  CHECK(model_of(scene, test::tiny_lidar4d())->loss_names() ==
        Names{"range", "patch_gradient", "chamfer"});
  CHECK(model_of(scene, test::tiny_lidar4d(Json{{"lidar4d", {{"chamfer_weight", 0.0}}}}))
            ->loss_names() == Names{"range", "patch_gradient"});

  SECTION("Chamfer: the output gradient of the list without it, plus its own, exactly") {
    // Without jitter the training forward equals render_rays(): its depths are the term's input.
    const Json no_jitter{{"render", {{"jitter", false}}}};
    const TrainConfig with = test::tiny_lidar4d(no_jitter);
    const TrainConfig without =
        test::tiny_lidar4d(merge_config_json(no_jitter, Json{{"lidar4d", {{"chamfer_weight", 0.0}}}}));
    auto a = model_of(scene, with), b = model_of(scene, without);
    a->set_frame(3, 14), b->set_frame(3, 14);
    const RayBatch batch = draw_ray_batch(scene, with, 5, 14);
    a->forward_backward(batch, 9, 14);
    b->forward_backward(batch, 9, 14);
    const auto ga = a->read_output_gradient(), gb = b->read_output_gradient();
    const auto out = b->render_rays(batch.origins, batch.directions, batch.n_rays);
    const size_t R = size_t(batch.n_rays);
    std::vector<float> depth(R), gt(R);
    size_t returns = 0;
    for (size_t i = 0; i < R; ++i) {
      const float mask = batch.label[i] > 0.5f ? 1.0f : 0.0f;
      depth[i] = out[3 * i] * mask, gt[i] = batch.range[i] * mask;
      returns += batch.label[i] > 0.5f;
    }
    REQUIRE(returns > 10);
    const auto c = render::ray_chamfer_loss(batch.directions, depth, gt, float(scene.norm.scale),
                                            float(with.lidar4d->chamfer_weight));
    CHECK(a->read_losses().value("chamfer") == c.loss);
    CHECK_FALSE(b->read_losses().has("chamfer"));
    size_t differ = 0, changed = 0;
    for (size_t i = 0; i < R; ++i) {
      const float expect = batch.label[i] > 0.5f ? gb[3 * i] + c.d_depth[i] : gb[3 * i];
      differ += ga[3 * i] != expect;
      differ += ga[3 * i + 1] != gb[3 * i + 1];
      differ += ga[3 * i + 2] != gb[3 * i + 2];
      changed += ga[3 * i] != gb[3 * i];
    }
    CHECK(differ == 0);
    CHECK(changed > 10);
  }
  SECTION("carving: the per-sample term leaves the output gradient, moves the parameters'") {
    const TrainConfig with = test::tiny_config(Json{{"render", {{"weights", {{"carve", 10.0}}}}}});
    auto a = model_of(scene, with), b = model_of(scene, test::tiny_config());
    const RayBatch batch = draw_ray_batch(scene, with, 5, 14);
    a->forward_backward(batch, 9, 14);
    b->forward_backward(batch, 9, 14);
    CHECK(a->read_output_gradient() == b->read_output_gradient());
    CHECK(a->read_gradient() != b->read_gradient());
    const LossReport la = a->read_losses(), lb = b->read_losses();
    CHECK(la.value("carve") > 0.0);
    CHECK_FALSE(lb.has("carve"));
    CHECK(la.value("depth") == lb.value("depth"));
    // The total: the records in list order, summed in float.
    CHECK(la.total() == float(la.value("depth")) + float(la.value("return")) +
                            float(la.value("intensity")) + float(la.value("grad")) +
                            float(la.value("carve")));
  }
}

// The device profile's loss_reduce: device: weight carving's per-ray terms summed on the device
// (render_loss_reduce's fixed tree) and the loss buffer read once, against each term reading its
// own values (host).
TEST_CASE("the loss read once under loss_reduce: device equals the terms' own reads",
          "[pipeline][model][loss_reduce][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = test::tiny_config(Json{{"render", {{"weights", {{"carve", 10.0}}}}}});
  std::unique_ptr<LidarNerfModel> host, device;
  for (const auto mode : {cl::LossReduce::Host, cl::LossReduce::Device}) {
    cl::DeviceProfile p = test::runtime().device_profile();
    p.loss_reduce = mode;
    test::ProfileScope scope(p);
    (mode == cl::LossReduce::Host ? host : device) = model_of(scene, c);
  }
  for (const long step : {14L, 15L}) {  // two batches, the second over the first's values
    CAPTURE(step);
    const RayBatch batch = draw_ray_batch(scene, c, 5, step);
    host->forward_backward(batch, 9, step);
    device->forward_backward(batch, 9, step);
    // The reduction touches no gradient: the same kernels, the same bits.
    CHECK(host->read_gradient() == device->read_gradient());
    test::runtime().finish();
    cl::LaunchTrace th, td;
    test::runtime().set_trace(&th);
    const LossReport la = host->read_losses();
    test::runtime().set_trace(&td);
    const LossReport lb = device->read_losses();
    test::runtime().set_trace(nullptr);
    // The range and patch values are the same buffer's words.
    for (const char* name : {"depth", "return", "intensity", "grad"})
      CHECK(la.value(name) == lb.value(name));
    const float a_carve = float(la.value("carve")), b_carve = float(lb.value("carve"));
    // Carving: the host sums the per-ray terms in double, the device in float (strided partials
    // and a tree over 200 rays); the terms are non-negative, so no cancellation: a few float
    // roundings of the sum, 1e-5 relative with room for any device's order.
    REQUIRE(a_carve > 0.0f);
    CHECK(test::sym_rel_err({b_carve}, {a_carve}, 0.0) <= 1e-5);
    CHECK(th.blocking_transfers.size() == 2);  // the loss buffer, carving's per-ray terms
    REQUIRE(td.blocking_transfers.size() == 1);
    CHECK(td.blocking_transfers[0].bytes == kLossBufferFloats * sizeof(float));
  }
}

// The pose-free step's one read under the gpu profile: the loss and the ray gradients' sums
// copied on the device into one buffer and read together, the same values as the two reads.
TEST_CASE("the loss and the ray-gradient sums in one read equal the two reads",
          "[pipeline][model][loss_reduce][pose_grad_sums][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = test::tiny_config(Json{{"render", {{"weights", {{"carve", 10.0}}}}}});
  for (const auto mode : {cl::LossReduce::Host, cl::LossReduce::Device}) {
    CAPTURE(cl::loss_reduce_name(mode));
    cl::DeviceProfile p = test::runtime().device_profile();
    p.loss_reduce = mode;
    std::unique_ptr<LidarNerfModel> m;
    {
      test::ProfileScope scope(p);
      m = model_of(scene, c);
    }
    const RayBatch batch = draw_ray_batch(scene, c, 5, 14);
    m->forward_backward(batch, 9, 14, true);
    test::runtime().finish();
    cl::LaunchTrace trace;
    test::runtime().set_trace(&trace);
    const LidarNerfModel::LossAndRaySums both = m->read_losses_and_ray_grad_sums();
    test::runtime().set_trace(nullptr);
    const LossReport l = m->read_losses();
    const render::RayGradSums s = m->read_ray_grad_sums();
    // Copies of the same words (the sums' kernel run again over the same gradients, a fixed
    // tree: the same bits).
    CHECK(both.loss.value("depth") == l.value("depth"));
    CHECK(both.loss.value("grad") == l.value("grad"));
    CHECK(both.loss.value("carve") == l.value("carve"));
    CHECK(both.sums.origin == s.origin);
    CHECK(both.sums.cross == s.cross);
    CHECK(s.cross.norm() > 0.0);
    // Host: carving's per-ray terms read beside the loss buffer and the sums.
    CHECK(trace.blocking_transfers.size() == (mode == cl::LossReduce::Device ? 1u : 2u));
  }
}
