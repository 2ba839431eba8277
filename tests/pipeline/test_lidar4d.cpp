// LiDAR4D as a method (method.md §2): its config section (read, written, refused), the ground
// split of the flow supervision's points, and the model on the 4D field: training bit-identical
// from one seed with a decreasing loss, the flow supervision's gradient reaching only the flow
// field, the Chamfer term, and renders that follow the frame's time.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "core/config.hpp"
#include "field/lidar4d_encoder.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "pipeline/model/render_view.hpp"
#include "pipeline/train/field_optimizer.hpp"
#include "pipeline/train/flow_points.hpp"
#include "pipeline/train/flow_supervision.hpp"
#include "pipeline/train/trainer.hpp"
#include "support/test_device.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {

using test::tiny_lidar4d;  // the LiDAR4D smoke preset shrunk to the tiny scene

std::string config_error(const Json& overrides) {
  try {
    resolve_config("lidar4d", "smoke", overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

struct Trained {
  std::vector<float> params;
  LossReport first, last;
  double flow_loss = 0.0;
};

Trained train_lidar4d(const Scene& scene, const TrainConfig& c, uint64_t seed,
                      const std::string& dir) {
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), model_capacity(c));
  GroundTruthPoseStep gt(scene, c);
  auto& flow = static_cast<FlowSupervision&>(model.add_loss(make_flow_supervision(
      test::runtime().device_profile().chamfer, test::tiny_dataset(), scene, c, seed)));
  TrainOptions opt;
  opt.run_dir = test::temp_dir(dir);
  opt.seed = seed;
  opt.show_progress = false;
  opt.policy = &gt;
  const TrainSummary s = train(model, scene, c, opt);
  return {model.params(), s.first_loss, s.last_loss, flow.last_value()};
}

}  // namespace

TEST_CASE("lidar4d config: presets resolve, the section round-trips, bad keys are refused",
          "[pipeline][config][lidar4d]") {
  for (const char* scale : {"smoke", "quick", "paper"}) {
    const TrainConfig c = resolve_config("lidar4d", scale);
    REQUIRE(c.four_d_encoder());
    CHECK(c.flow_supervision());
    const TrainConfig back = train_config_from_json(train_config_to_json(c), "round trip");
    CHECK(train_config_to_json(back) == train_config_to_json(c));
    CHECK(back.hash() == c.hash());
  }
  // The paper preset keeps LiDAR4D's encoder sizes.
  const TrainConfig p = resolve_config("lidar4d", "paper");
  CHECK(p.lidar4d->encoder.static_hash.levels == 8);
  CHECK(p.lidar4d->encoder.static_hash.features == 4);
  CHECK(p.lidar4d->encoder.static_hash.base_resolution == 512.0f);
  CHECK(p.lidar4d->encoder.planes.scales == 4);
  CHECK(p.lidar4d->network_lr_scale == Approx(0.1));
  // A static_hash object that names one key keeps LiDAR4D's other values.
  const TrainConfig one = resolve_config(
      "lidar4d", "paper", Json{{"lidar4d", {{"encoder", {{"static_hash", {{"log2_table_size", 15}}}}}}}});
  CHECK(one.lidar4d->encoder.static_hash.log2_table_size == 15);
  CHECK(one.lidar4d->encoder.static_hash.levels == 8);
  CHECK(config_error(Json{{"lidar4d", {{"encoder", {{"planes", {{"resolutoin", 8}}}}}}}})
            .find("resolutoin") != std::string::npos);
  CHECK(config_error(Json{{"lidar4d", {{"flow", {{"steps", 3}}}}}}).find("steps") !=
        std::string::npos);
  CHECK(config_error(Json{{"lidar4d", {{"chamfer", 1.0}}}}).find("chamfer") != std::string::npos);
  // The ray-drop refinement: the presets' U-Net sizes, a partial unet object keeping the
  // preset's other keys, bad keys in refine and in refine.unet refused by name.
  const TrainConfig smoke = resolve_config("lidar4d", "smoke");
  REQUIRE(smoke.ray_drop_refinement());
  CHECK(smoke.flow_supervision());
  CHECK(smoke.lidar4d->refine->frames == 2);
  CHECK(smoke.lidar4d->refine->unet.depth == 2);
  CHECK(smoke.lidar4d->refine->unet.steps == 4);
  CHECK(resolve_config("lidar4d", "quick").lidar4d->refine->frames == 8);
  CHECK(resolve_config("lidar4d", "quick").lidar4d->refine->unet.steps == 250);
  CHECK(p.lidar4d->refine->frames == 0);
  CHECK(p.lidar4d->refine->unet.channels == 32);
  CHECK(p.lidar4d->refine->unet.steps == 1000);
  const TrainConfig r = resolve_config(
      "lidar4d", "smoke",
      Json{{"lidar4d", {{"refine", {{"frames", 5}, {"unet", {{"lr", 5e-4}}}}}}}});
  CHECK(r.ray_drop_refinement());
  CHECK(r.lidar4d->refine->frames == 5);
  CHECK(r.lidar4d->refine->unet.lr == Approx(5e-4));
  CHECK(r.lidar4d->refine->unet.channels == 16);
  const TrainConfig r_back = train_config_from_json(train_config_to_json(r), "round trip");
  CHECK(train_config_to_json(r_back) == train_config_to_json(r));
  CHECK(r_back.hash() == r.hash());
  CHECK(r.hash() != smoke.hash());
  // Each optional part is on exactly when its section is present.
  const TrainConfig bare =
      resolve_config("lidar4d", "smoke", Json{{"lidar4d", {{"refine", nullptr}, {"flow", nullptr}}}});
  CHECK_FALSE(bare.ray_drop_refinement());
  CHECK_FALSE(bare.flow_supervision());
  CHECK_FALSE(train_config_to_json(bare)["lidar4d"].contains("refine"));
  CHECK(train_config_from_json(train_config_to_json(bare), "rt").hash() == bare.hash());
  CHECK(config_error(Json{{"lidar4d", {{"refine", {{"enabled", false}}}}}})
            .find("lidar4d.refine: 'enabled' is not a key") != std::string::npos);
  const std::string bad_refine = config_error(Json{{"lidar4d", {{"refine", {{"frmaes", 2}}}}}});
  CHECK(bad_refine.find("frmaes") != std::string::npos);
  CHECK(bad_refine.find("refine") != std::string::npos);
  const std::string bad_unet =
      config_error(Json{{"lidar4d", {{"refine", {{"unet", {{"chanels", 16}}}}}}}});
  CHECK(bad_unet.find("chanels") != std::string::npos);
  CHECK(bad_unet.find("refine.unet") != std::string::npos);
  CHECK(config_error(Json{{"lidar4d", {{"refine", {{"frames", -1}}}}}}).find("frames") !=
        std::string::npos);
  CHECK(config_error(Json{{"lidar4d", {{"refine", {{"unet", {{"channels", 24}}}}}}}})
            .find("channels") != std::string::npos);
  // Other methods' configs carry no lidar4d section and refuse one.
  CHECK_FALSE(resolve_config("lidar-nerf", "smoke").lidar4d.has_value());
  CHECK_THROWS_AS(resolve_config("lidar-nerf", "smoke", Json{{"lidar4d", Json::object()}}),
                  ConfigError);
}

TEST_CASE("flow points: the ground is the densest low height bin, split and subsampled",
          "[pipeline][lidar4d]") {
  FlowSupervisionConfig c;
  // A road at z = −1.73 m (a grid of returns), a wall at x = 8 m up to +3 m and a car roof at
  // z = −0.3 m: the ground is found at the road whatever the mounting height.
  std::vector<PointXYZI> scan;
  for (int i = -20; i <= 20; ++i)
    for (int j = -20; j <= 20; ++j) scan.push_back({0.5f * i, 0.5f * j, -1.73f, 0.1f});
  for (int i = 0; i < 200; ++i) scan.push_back({8.0f, 0.05f * i - 5.0f, -1.7f + 0.0235f * i, 0.2f});
  for (int i = 0; i < 300; ++i) scan.push_back({3.0f + 0.01f * i, 2.0f, -0.3f, 0.3f});
  const double z = ground_height(scan, c, "scan");
  CHECK(z == Approx(-1.73).margin(c.ground_bin_m));
  for (auto& p : scan) p.z += 0.5f;  // the same street seen from a sensor 0.5 m lower
  CHECK(ground_height(scan, c, "scan") == Approx(-1.23).margin(c.ground_bin_m));
  CHECK_THROWS_WITH(ground_height({{100.0f, 0.0f, -1.0f, 0.0f}}, c, "far scan"),
                    Catch::Contains("far scan"));

  const Dataset& d = test::tiny_dataset();
  const Scene scene = make_scene(d);
  c.points = 300;
  c.ground_points = 50;
  const auto a = flow_points(d, scene, c, 5), b = flow_points(d, scene, c, 5);
  REQUIRE(a.size() == d.frames.size());
  size_t ground = 0;
  for (size_t k = 0; k < a.size(); ++k) {
    CHECK(a[k].moving.size() <= 300);
    CHECK(a[k].ground.size() <= 50);
    CHECK(a[k].moving == b[k].moving);  // same seed, same points
    ground += a[k].ground.size();
  }
  CHECK(ground > 0);
  // Ground points lie below the moving ones on average (the normalised world's z is up).
  double zg = 0, zm = 0;
  for (const auto& p : a[0].ground) zg += p.z() / double(a[0].ground.size());
  for (const auto& p : a[0].moving) zm += p.z() / double(a[0].moving.size());
  CHECK(zg < zm);
  CHECK(flow_points(d, scene, c, 6)[0].moving != a[0].moving);
}

TEST_CASE("lidar4d model: bit-identical training, decreasing loss, flow gradient in its slice",
          "[pipeline][lidar4d]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = tiny_lidar4d();
  const Trained a = train_lidar4d(scene, c, 9, "l4d_a"), b = train_lidar4d(scene, c, 9, "l4d_b");
  CHECK(a.params == b.params);
  CHECK(a.flow_loss > 0.0);
  CHECK(a.last.total() < a.first.total());
  const Trained other = train_lidar4d(scene, c, 10, "l4d_c");
  CHECK(other.params != a.params);

  // A flow loss term's gradient reaches the flow field's parameters only: a term of the test's
  // own (FieldPass::flow, as the flow supervision's) in a model's step.
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), model_capacity(c));
  model.init_params(3);
  struct PullFlow final : LossTerm {
    const char* name() const override { return "pull_flow"; }
    void add_field_gradient(FieldPass& field) override {
      const std::vector<float> x = {0.1f, 0.2f, -0.1f, -0.3f, 0.0f, 0.05f};
      // Pull every flow component to 0.01, weighted far above the batch's loss, whose gradient
      // reaches the flow field too (through the 4D encoder's flowed neighbours).
      value = field.flow(x, 2, [](const std::vector<float>& f, std::vector<float>& d) {
        double l = 0;
        for (size_t i = 0; i < f.size(); ++i) {
          l += 1e3 * double(f[i] - 0.01f) * double(f[i] - 0.01f);
          d[i] = 2e3f * (f[i] - 0.01f);
        }
        return l;
      });
    }
    void report(LossReport& r, const std::vector<float>&) const override { r.add(name(), value); }
    double value = 0.0;
  };
  auto& pull = static_cast<PullFlow&>(model.add_loss(std::make_unique<PullFlow>()));
  const RayBatch batch = draw_ray_batch(scene, c, 4, 1);
  model.set_frame(batch.frame, int(scene.T_world_lidar.size()));
  model.forward_backward(batch, 4, 1);
  const double value = pull.value;
  CHECK(value > 0.0);
  CHECK(model.read_losses().value("pull_flow") == value);
  // The term's share of the step's gradient lies in the flow field's slice only.
  const std::vector<float> g = model.read_term_gradient();
  const auto& off = model.four_d_encoder()->offsets();
  const size_t lo = off.flow, hi = off.end;  // the encoder's slice starts at 0
  size_t in = 0, out = 0;
  for (size_t i = 0; i < g.size(); ++i) ((i >= lo && i < hi) ? in : out) += g[i] != 0.0f ? 1 : 0;
  CHECK(in > 0);
  CHECK(out == 0);
  // Repeated steps pull the flow toward the target: the loss falls.
  double last = value;
  FieldOptimizer optim(model, c);
  for (int it = 0; it < 20; ++it) {
    model.forward_backward(batch, 4, 2 + it);
    optim.step(1e-2f);
    last = pull.value;
  }
  CHECK(last < 0.5 * value);
}

TEST_CASE("lidar4d model: the Chamfer term and renders at the frame's time",
          "[pipeline][lidar4d]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = tiny_lidar4d();
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), model_capacity(c));
  model.init_params(4);
  const RayBatch b = draw_ray_batch(scene, c, 4, 1);
  model.set_frame(b.frame, int(scene.T_world_lidar.size()));
  model.forward_backward(b, 4, 1);
  CHECK(model.read_losses().value("chamfer") > 0.0);
  const TrainConfig off = tiny_lidar4d(Json{{"lidar4d", {{"chamfer_weight", 0.0}}}});
  LidarNerfModel plain(test::runtime(), off, float(scene.norm.scale), model_capacity(off));
  plain.init_params(4);
  plain.forward_backward(b, 4, 1);
  CHECK_FALSE(plain.read_losses().has("chamfer"));
  // The Chamfer term changes the parameter gradient (it adds dL/d depth per ray).
  CHECK(model.read_gradient() != plain.read_gradient());

  // A trained 4D field renders one pose differently at two frames' times, and the same at the
  // same time; a model without a time ignores the frame.
  const Pose& T = test::tiny_dataset().frames[3].T_world_lidar;
  const Trained t = train_lidar4d(scene, c, 2, "l4d_render");
  model.set_params(t.params);
  const RangeImage r3 = render_view(model, scene, T, 512, 3);
  const RangeImage r3b = render_view(model, scene, T, 512, 3);
  const RangeImage r10 = render_view(model, scene, T, 512, 10);
  CHECK(r3.range == r3b.range);
  CHECK(r3.range != r10.range);
  CHECK(render_view(model, scene, T, 512) .range == r3.range);  // frame 3 is nearest to its pose
  CHECK(nearest_frame(scene, T) == 3);
}

TEST_CASE("lidar4d model: separate intensity and ray-drop heads stay separate in training",
          "[pipeline][lidar4d]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = tiny_lidar4d();
  REQUIRE(c.lidar4d->separate_heads);
  CHECK(c.lidar4d->ray_drop_label_smoothing == Approx(0.2));
  const TrainConfig one = tiny_lidar4d(Json{{"lidar4d", {{"separate_heads", false}}}});
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), model_capacity(c));
  LidarNerfModel shared(test::runtime(), one, float(scene.norm.scale), model_capacity(one));
  const field::ParamSlice& head = model.layout().slice("head_mlp");
  CHECK(head.count > shared.layout().slice("head_mlp").count);

  // The head's layout (field/mlp.hpp): per layer W_t[rows][out_pad] then the bias row; two
  // towers of head_hidden, the first return probability's, the second intensity's. Past the
  // first layer a weight between the towers is structurally zero, before and after training.
  const int hidden = c.field.head_hidden, layers = c.field.head_layers;
  const int rows0 = c.field.geo_features + 6 * c.field.dir_frequencies;
  const auto off_tower = [&](const std::vector<float>& p) {
    size_t at = head.offset + size_t(rows0 + 1) * size_t(2 * hidden), zeros = 0, count = 0;
    for (int l = 1; l <= layers; ++l) {
      const int out = l == layers ? 2 : 2 * hidden, out_pad = (out + 15) / 16 * 16;
      const int per_out = out / 2;
      for (int i = 0; i < 2 * hidden; ++i)
        for (int o = 0; o < out; ++o)
          if (i / hidden != o / per_out) {
            ++count;
            zeros += p[at + size_t(i) * out_pad + size_t(o)] == 0.0f ? 1 : 0;
          }
      at += size_t(2 * hidden + 1) * size_t(out_pad);
    }
    CHECK(at == head.offset + head.count);
    return std::make_pair(zeros, count);
  };
  model.init_params(5);
  const auto init = off_tower(model.params());
  CHECK(init.second > 0);
  CHECK(init.first == init.second);
  const Trained t = train_lidar4d(scene, c, 5, "l4d_heads");
  const auto trained = off_tower(t.params);
  CHECK(trained.first == trained.second);
  // The towers themselves trained: the head's first layer moved.
  const std::vector<float> st = model.params();
  size_t moved = 0;
  for (size_t i = head.offset; i < head.offset + head.count; ++i)
    moved += t.params[i] != st[i] ? 1 : 0;
  CHECK(moved > head.count / 4);
  // Label smoothing moves the return term only: same batch, same parameters, the depth and
  // intensity terms are equal and the return term differs.
  const TrainConfig unsmoothed = tiny_lidar4d(Json{{"lidar4d", {{"ray_drop_label_smoothing", 0.0}}}});
  LidarNerfModel plain(test::runtime(), unsmoothed, float(scene.norm.scale), model_capacity(unsmoothed));
  plain.init_params(5);
  const RayBatch b = draw_ray_batch(scene, c, 6, 1);
  model.set_frame(b.frame, int(scene.T_world_lidar.size()));
  plain.set_frame(b.frame, int(scene.T_world_lidar.size()));
  model.forward_backward(b, 6, 1);
  plain.forward_backward(b, 6, 1);
  const LossReport ls = model.read_losses(), lp = plain.read_losses();
  CHECK(ls.value("depth") == lp.value("depth"));
  CHECK(ls.value("intensity") == lp.value("intensity"));
  CHECK(ls.value("return") != lp.value("return"));
}

TEST_CASE("the field's optimiser: LiDAR4D's two groups at their rates, its state checked",
          "[pipeline][lidar4d][optim]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = tiny_lidar4d();
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), model_capacity(c));
  model.init_params(7);
  const auto groups = model.trainable().groups;
  REQUIRE(groups.size() == 2);
  CHECK(groups[0].offset == 0);
  CHECK(groups[0].count == model.layout().slice("hash_grid").offset +
                               model.four_d_encoder()->offsets().flow);
  CHECK(groups[1].offset == groups[0].count);
  CHECK(groups[1].offset + groups[1].count == model.n_params());
  CHECK(groups[1].lr_scale == c.lidar4d->network_lr_scale);
  // Adam's first step moves every parameter with a gradient by its group's rate against the
  // gradient's sign (ε 1e-15): the encodings by lr, the flow field and the MLPs by lr · scale.
  const RayBatch b = draw_ray_batch(scene, c, 7, 1);
  model.set_frame(b.frame, int(scene.T_world_lidar.size()));
  const auto p0 = model.params();
  model.forward_backward(b, 7, 1);
  const auto g = model.read_gradient();
  FieldOptimizer optim(model, c);
  const float lr = 1e-2f;
  optim.step(lr);
  const auto p1 = model.params();
  size_t checked[2] = {0, 0}, bad = 0;
  for (int k = 0; k < 2; ++k) {
    const double rate = double(lr) * groups[size_t(k)].lr_scale;
    for (size_t i = groups[size_t(k)].offset; i < groups[size_t(k)].offset + groups[size_t(k)].count; ++i) {
      if (std::abs(g[i]) < 1e-8f) continue;
      ++checked[k];
      bad += std::abs(double(p1[i]) - double(p0[i]) + rate * (g[i] > 0 ? 1.0 : -1.0)) > 1e-3 * rate;
    }
  }
  CHECK(checked[0] > 100);
  CHECK(checked[1] > 100);
  CHECK(bad == 0);
  CHECK(optim.steps() == 1);
  // Its state round-trips; a state of another model's size is refused, naming both counts.
  const OptimizerState st = optim.state();
  CHECK(st.m.size() == model.n_params());
  FieldOptimizer again(model, c);
  again.set_state(st);
  CHECK(again.steps() == 1);
  CHECK(again.state().v == st.v);
  OptimizerState wrong = st;
  wrong.m.pop_back();
  CHECK_THROWS_WITH(again.set_state(wrong),
                    Catch::Contains(std::to_string(model.n_params()) + " parameters") &&
                        Catch::Contains(std::to_string(model.n_params() - 1)));
  CHECK_THROWS_WITH(model.set_params(wrong.m), Catch::Contains("model parameters"));
}
