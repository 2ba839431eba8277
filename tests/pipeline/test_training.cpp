// Training on a tiny synthetic sequence: bit-identical parameters from one seed, resume from a
// checkpoint equal to the uninterrupted run, divergence stopping with the last good checkpoint
// kept, ray batches keyed by (seed, step), and a loss that decreases.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "core/config.hpp"
#include "field/hash_grid_encoder.hpp"
#include "field/mlp.hpp"
#include "pipeline/train/checkpoint.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "pipeline/model/render_view.hpp"
#include "pipeline/train/trainer.hpp"
#include "support/test_device.hpp"
#include "render_fixtures.hpp"
#include "tiny_scene.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {

std::vector<float> train_params(const Scene& scene, const TrainConfig& c, uint64_t seed,
                                const std::string& dir, long stop_at = -1, bool resume = true,
                                bool reuse_coarse = true) {
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale),
                       std::max(c.schedule.rays_per_batch, c.schedule.render_chunk_rays));
  model.set_reuse_coarse_encodings(reuse_coarse);
  TrainOptions opt;
  opt.run_dir = dir;
  opt.seed = seed;
  opt.stop_at = stop_at;
  opt.resume = resume;
  opt.show_progress = false;
  train(model, scene, c, opt);
  return model.params();
}

}  // namespace

TEST_CASE("ray batches are keyed by (seed, step) and visit training frames only",
          "[pipeline][batch]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = test::tiny_config();
  REQUIRE(scene.test == std::vector<int>{13});
  const auto a = draw_ray_batch(scene, c, 3, 5), b = draw_ray_batch(scene, c, 3, 5);
  CHECK(a.pixels == b.pixels);
  CHECK(a.origins == b.origins);
  CHECK(draw_ray_batch(scene, c, 4, 5).pixels != a.pixels);
  // One epoch visits every training frame once; test frames never.
  std::vector<int> seen;
  for (long s = 0; s < long(scene.train.size()); ++s) seen.push_back(batch_frame(scene, 3, s));
  std::sort(seen.begin(), seen.end());
  CHECK(seen == scene.train);
  // Epoch 0 is a patch epoch: rows × cols blocks of adjacent pixels; epoch 1 is not.
  CHECK(a.patches);
  const int W = scene.sensor.width, PR = c.render.patch_rows, PC = c.render.patch_cols;
  for (int i = 0; i < PR * PC; ++i)
    CHECK(a.pixels[size_t(i)] == a.pixels[0] + (i / PC) * W + i % PC);
  CHECK_FALSE(draw_ray_batch(scene, c, 3, long(scene.train.size())).patches);
  // Ground truth is the frame's normalised range.
  const auto& img = scene.images[size_t(a.frame)];
  CHECK(a.range[7] == img.range[size_t(a.pixels[7])]);
}

TEST_CASE("same seed gives bit-identical parameters; another seed differs",
          "[pipeline][train][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = test::tiny_config();
  const auto p1 = train_params(scene, c, 7, test::temp_dir("det_a"));
  const auto p2 = train_params(scene, c, 7, test::temp_dir("det_b"));
  const auto p3 = train_params(scene, c, 8, test::temp_dir("det_c"));
  REQUIRE(p1.size() == p2.size());
  CHECK(p1 == p2);
  CHECK(p1 != p3);
}

TEST_CASE("reusing the coarse pass's encodings is exact: same parameters as re-encoding",
          "[pipeline][train][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = test::tiny_config();
  REQUIRE(c.render.n_importance > 0);
  const auto reuse = train_params(scene, c, 7, test::temp_dir("reuse_on"));
  const auto again = train_params(scene, c, 7, test::temp_dir("reuse_off"), -1, true, false);
  REQUIRE(reuse.size() == again.size());
  size_t differ = 0;
  for (size_t i = 0; i < reuse.size(); ++i) differ += reuse[i] != again[i];
  CHECK(differ == 0);
}

TEST_CASE("resuming from a checkpoint reproduces the uninterrupted run",
          "[pipeline][train][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = test::tiny_config();
  const auto full = train_params(scene, c, 11, test::temp_dir("resume_full"));
  const std::string dir = test::temp_dir("resume_split");
  const auto half = train_params(scene, c, 11, dir, 6);
  CHECK(load_checkpoint(checkpoint_path(dir)).step == 6);
  CHECK(half != full);
  const auto resumed = train_params(scene, c, 11, dir);
  CHECK(load_checkpoint(checkpoint_path(dir)).step == 12);
  CHECK(resumed == full);
  // A different config refuses the checkpoint instead of silently mixing runs.
  const TrainConfig other = test::tiny_config(Json{{"optim", {{"lr", 0.02}}}});
  CHECK_THROWS_AS(train_params(scene, other, 11, dir), ConfigError);
}

TEST_CASE("an absurd learning rate stops with a NumericError and keeps the last good checkpoint",
          "[pipeline][train][device]") {
  const Scene scene = make_scene(test::tiny_dataset());
  const TrainConfig c = test::tiny_config(
      Json{{"optim", {{"lr", 1e6}}}, {"schedule", {{"checkpoint_every", 1}, {"log_every", 1}}}});
  const std::string dir = test::temp_dir("diverge");
  std::string msg;
  try {
    train_params(scene, c, 1, dir);
  } catch (const NumericError& e) {
    msg = e.what();
  }
  INFO(msg);
  CHECK(msg.find("diverged") != std::string::npos);
  CHECK(msg.find("last good checkpoint") != std::string::npos);
  const Checkpoint ck = load_checkpoint(checkpoint_path(dir));
  CHECK(ck.step >= 1);
  CHECK(ck.step < c.schedule.iterations);
  for (float v : ck.array("params")) REQUIRE(std::isfinite(v));
}

TEST_CASE("training lowers the loss and renders full images", "[pipeline][train][device]") {
  const Dataset& d = test::tiny_dataset();
  const Scene scene = make_scene(d);
  const TrainConfig c = test::tiny_config(
      Json{{"schedule", {{"iterations", 120}, {"checkpoint_every", 0}, {"log_every", 1}}}});
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), 512);
  TrainOptions opt;
  opt.run_dir = test::temp_dir("loss_down");
  opt.seed = 3;
  opt.show_progress = false;
  const TrainSummary s = train(model, scene, c, opt);
  CHECK(s.finished);
  // Compare the mean loss of the first and the last 12 logged steps (one frame per step).
  std::vector<double> losses;
  std::ifstream in(opt.run_dir + "/train_log.jsonl");
  for (std::string line; std::getline(in, line);) losses.push_back(Json::parse(line)["loss"]["total"]);
  REQUIRE(losses.size() == 120);
  double first = 0, last = 0;
  for (int i = 0; i < 12; ++i) {
    first += losses[size_t(i)];
    last += losses[losses.size() - 1 - size_t(i)];
  }
  INFO("first " << first / 12 << " last " << last / 12);
  CHECK(last < 0.5 * first);
  const RangeImage img = render_view(model, scene, d.frames[13].T_world_lidar, 512);
  CHECK(img.height == 16);
  CHECK(img.width == 128);
  for (float v : img.range) REQUIRE(std::isfinite(v));
}

TEST_CASE("early ray termination: exact while no ray terminates, within its threshold after",
          "[pipeline][train][device]") {
  const Dataset& d = test::tiny_dataset();
  const Scene scene = make_scene(d);
  // At initialisation no ray is opaque enough to terminate: the compacted path must then give
  // the exact path's parameters bit for bit (it runs every kernel of the compaction).
  const TrainConfig exact = test::tiny_config();
  const TrainConfig early = test::tiny_config(Json{{"render", {{"stop_transmittance", 1e-4}}}});
  const auto p_exact = train_params(scene, exact, 7, test::temp_dir("ert_exact"));
  const auto p_early = train_params(scene, early, 7, test::temp_dir("ert_early"));
  REQUIRE(p_exact.size() == p_early.size());
  CHECK(p_exact == p_early);

  // A trained field terminates rays; rendering with the threshold then drops at most about
  // that much weight per ray (coarse transmittance below eps, one more coarse bin of margin).
  const TrainConfig c = test::tiny_config(
      Json{{"schedule", {{"iterations", 150}, {"checkpoint_every", 0}}}});
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), 512);
  const std::vector<float> st = test::opaque_state(model, scene, c, "ert_trained");
  const float eps = 1e-3f;
  TrainConfig ce = c;
  ce.render.stop_transmittance = eps;
  LidarNerfModel cut(test::runtime(), ce, float(scene.norm.scale), 512);
  cut.set_params(st);
  // 512 rays of the test frame (13), in the normalised frame.
  std::vector<float> o, dir;
  image_rays(scene, normalize_pose(d.frames[13].T_world_lidar, scene.norm), 600, 1112, o, dir);
  const auto full = model.render_rays(o, dir, 512);
  const auto part = cut.render_rays(o, dir, 512);
  const auto live = cut.live_counts();
  const int M = c.render.n_samples + c.render.n_importance;
  long n_live = 0, cut_rays = 0;
  for (int v : live) {
    n_live += v;
    cut_rays += v < M;
  }
  INFO("rays cut " << cut_rays << " of 512, live samples " << n_live << " of " << 512 * M);
  CHECK(cut_rays > 50);
  const float far = c.render.far_m * float(scene.norm.scale);
  const double worst_depth = test::worst_channel_diff(full, part, 0), worst_prob = test::worst_channel_diff(full, part, 1);
  INFO("worst |depth diff| " << worst_depth << " (far " << far << "), worst |prob diff| " << worst_prob);
  CHECK(worst_depth <= 4 * eps * far);
  CHECK(worst_prob <= 4 * eps);

  // Coarse waves (render.coarse_waves): the coarse pass stops rays too. The live prefix must
  // match the one-wave pass (the termination index is found over the same weights); the
  // output may move only through the importance pdf, which loses the weight behind
  // termination (< eps): bounded like the termination itself. Fewer coarse samples evaluated.
  TrainConfig cw = ce;
  cw.render.coarse_waves = 4;
  LidarNerfModel waves(test::runtime(), cw, float(scene.norm.scale), 512);
  waves.set_params(st);
  const auto wave_out = waves.render_rays(o, dir, 512);
  const auto wave_live = waves.live_counts();
  const int S = c.render.n_samples;
  INFO("coarse samples evaluated: one wave " << cut.coarse_evaluated() << ", four waves "
                                             << waves.coarse_evaluated() << " of " << 512 * S);
  CHECK(cut.coarse_evaluated() == 512L * S);
  CHECK(waves.coarse_evaluated() < 512L * S * 9 / 10);
  long same_live = 0;
  for (size_t k = 0; k < live.size(); ++k) same_live += live[k] == wave_live[k];
  INFO("rays whose live count matches: " << same_live << " of 512");
  CHECK(same_live >= 500);
  const double wave_depth = test::worst_channel_diff(full, wave_out, 0),
               wave_prob = test::worst_channel_diff(full, wave_out, 1);
  INFO("waves: worst |depth diff| " << wave_depth << ", worst |prob diff| " << wave_prob);
  CHECK(wave_depth <= 4 * eps * far);
  CHECK(wave_prob <= 4 * eps);

  // Head band (render.head_weight_threshold): depth is the density's alone (bit-identical);
  // return probability and intensity lose at most the band-outside samples' weight each.
  const float thr = 1e-4f;
  TrainConfig cb = ce;
  cb.render.head_weight_threshold = thr;
  LidarNerfModel band(test::runtime(), cb, float(scene.norm.scale), 512);
  band.set_params(st);
  const auto band_out = band.render_rays(o, dir, 512);
  INFO("head rows " << band.head_rows() << " of " << n_live << " live samples");
  CHECK(band.head_rows() > 0);
  CHECK(band.head_rows() < n_live * 3 / 4);
  CHECK(test::worst_channel_diff(part, band_out, 0) == 0.0);  // depth bit-identical
  const double band_prob = test::worst_channel_diff(part, band_out, 1),
               band_int = test::worst_channel_diff(part, band_out, 2);
  INFO("band: worst |prob diff| " << band_prob << ", worst |intensity diff| " << band_int);
  CHECK(band_prob <= M * thr);
  CHECK(band_int <= M * thr);

  // Its backward. The head's parameters do not move the band: central differences of the
  // step's loss. The density MLP's and the grid's may (and they move the importance samples,
  // which the backward holds fixed as the peers do, so differences do not apply to them at
  // all): against the backward without the band, which they must match up to the dropped
  // head outputs' share.
  const RayBatch b = draw_ray_batch(scene, cb, 7, 160);
  auto gradient_of = [&](LidarNerfModel& m) {
    m.set_params(st);
    m.forward_backward(b, 7, 160);
    m.read_losses();
    return m.read_gradient();
  };
  const auto grad_cut = gradient_of(cut);
  const auto grad = gradient_of(band);
  auto loss_at = [&](size_t k, float v) {
    std::vector<float> sp = st;
    sp[k] += v;
    band.set_params(sp);
    band.forward_backward(b, 7, 160);
    return double(band.read_losses().total());
  };
  const auto& hs = band.layout().slice("head_mlp");
  std::vector<size_t> idx(hs.count);
  for (size_t k = 0; k < hs.count; ++k) idx[k] = hs.offset + k;
  std::partial_sort(idx.begin(), idx.begin() + 4, idx.end(), [&](size_t a, size_t c2) {
    return std::fabs(grad[a]) > std::fabs(grad[c2]);
  });
  for (int j = 0; j < 4; ++j) {  // the 4 head parameters with the largest gradient
    const size_t k = idx[size_t(j)];
    const float h = 1e-3f;
    const double fd = (loss_at(k, h) - loss_at(k, -h)) / (2.0 * h);
    INFO("head parameter " << k << ": analytic " << grad[k] << ", numeric " << fd);
    CHECK(std::fabs(fd - grad[k]) <= 0.02 * std::fabs(grad[k]) + 1e-4);
  }
  for (const char* slice : {"density_mlp", "hash_grid"}) {
    const auto& sl = band.layout().slice(slice);
    double diff = 0, norm = 0;
    for (size_t k = sl.offset; k < sl.offset + sl.count; ++k) {
      diff += (double(grad[k]) - grad_cut[k]) * (double(grad[k]) - grad_cut[k]);
      norm += double(grad_cut[k]) * grad_cut[k];
    }
    INFO(slice << ": |g_band − g_all| / |g_all| = " << std::sqrt(diff / norm));
    CHECK(norm > 0);
    CHECK(std::sqrt(diff / norm) < 1e-3);
  }
}

TEST_CASE("coarse waves: exact while no ray terminates", "[pipeline][train][device]") {
  // At initialisation nothing terminates: every wave runs on every ray, and the split coarse
  // pass (gather, encode, density, scatter per wave) must give the one-pass parameters bit for bit.
  const Dataset& d = test::tiny_dataset();
  const Scene scene = make_scene(d);
  const TrainConfig one = test::tiny_config(Json{{"render", {{"stop_transmittance", 1e-4}}}});
  const TrainConfig four = test::tiny_config(
      Json{{"render", {{"stop_transmittance", 1e-4}, {"coarse_waves", 4}}}});
  const auto p_one = train_params(scene, one, 7, test::temp_dir("waves_one"));
  const auto p_four = train_params(scene, four, 7, test::temp_dir("waves_four"));
  REQUIRE(p_one.size() == p_four.size());
  CHECK(p_one == p_four);
}

TEST_CASE("early termination of uniform-only sampling: exact at initialisation, bounded after",
          "[pipeline][train][device]") {
  // GeoNLF's and SG-NLF's sampling (uniform samples only) with render.stop_transmittance: a
  // density-only pass finds the termination point, the training pass runs on the live prefix.
  const Dataset& d = test::tiny_dataset();
  const Scene scene = make_scene(d);
  const Json uniform{{"n_importance", 0}, {"n_samples", 48}};
  const TrainConfig exact = test::tiny_config(Json{{"render", uniform}});
  Json early_j = uniform, waves_j = uniform;
  early_j["stop_transmittance"] = 1e-4;
  waves_j["stop_transmittance"] = 1e-4;
  waves_j["coarse_waves"] = 4;
  const TrainConfig early = test::tiny_config(Json{{"render", early_j}});
  const TrainConfig waves = test::tiny_config(Json{{"render", waves_j}});
  // Nothing terminates at initialisation: the three must train the same parameters bit for bit.
  const auto p_exact = train_params(scene, exact, 7, test::temp_dir("uert_exact"));
  CHECK(p_exact == train_params(scene, early, 7, test::temp_dir("uert_early")));
  CHECK(p_exact == train_params(scene, waves, 7, test::temp_dir("uert_waves")));

  // On an opaque field: fewer samples evaluated, the output within the threshold's bound.
  const TrainConfig c = test::tiny_config(
      Json{{"render", uniform}, {"schedule", {{"iterations", 150}, {"checkpoint_every", 0}}}});
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), 512);
  const std::vector<float> st = test::opaque_state(model, scene, c, "uert_trained");
  const float eps = 1e-3f;
  std::vector<float> o, dir;
  image_rays(scene, normalize_pose(d.frames[13].T_world_lidar, scene.norm), 600, 1112, o, dir);
  const auto full = model.render_rays(o, dir, 512);
  const float far = c.render.far_m * float(scene.norm.scale);
  for (int n_waves : {1, 4}) {
    TrainConfig ce = c;
    ce.render.stop_transmittance = eps;
    ce.render.coarse_waves = n_waves;
    LidarNerfModel cut(test::runtime(), ce, float(scene.norm.scale), 512);
    cut.set_params(st);
    const auto part = cut.render_rays(o, dir, 512);
    const long S = c.render.n_samples;
    INFO(n_waves << " wave(s): live samples " << cut.live_samples() << ", density-pass samples "
                 << cut.coarse_evaluated() << " of " << 512 * S);
    CHECK(cut.live_samples() < 512 * S * 6 / 10);
    if (n_waves > 1) CHECK(cut.coarse_evaluated() < 512 * S * 7 / 10);
    const double worst_depth = test::worst_channel_diff(full, part, 0),
                 worst_prob = test::worst_channel_diff(full, part, 1);
    INFO("worst |depth diff| " << worst_depth << " (far " << far << "), worst |prob diff| " << worst_prob);
    CHECK(worst_depth <= 4 * eps * far);
    CHECK(worst_prob <= 4 * eps);
  }
}

TEST_CASE("the embedded module configs reach the modules: field.grid, optim.adam",
          "[pipeline][config]") {
  const Scene scene = make_scene(test::tiny_dataset());
  // The defaults the presets keep: the deterministic fp32 grid, Adam without weight decay.
  {
    const TrainConfig c = test::tiny_config();
    LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), 512);
    const field::HashGridConfig& g =
        dynamic_cast<const field::HashGridEncoder&>(model.encoder()).grid().config();
    CHECK(g.deterministic);
    CHECK_FALSE(g.half_table);
    CHECK(g.schedule == "auto");
    CHECK(g.levels == 8);  // the smoke preset's
    CHECK(FieldOptimizer(model, c).config().weight_decay == 0.0f);
  }
  // Options no training config could set before (the model fixed them): now keys.
  const TrainConfig c = test::tiny_config(
      Json{{"field", {{"grid", {{"deterministic", false}, {"half_table", true},
                                {"schedule", "per_point"}, {"levels", 6}}}}},
           {"optim", {{"adam", {{"weight_decay", 1e-3}, {"beta2", 0.95}}}}}});
  CHECK(c.hash() != test::tiny_config().hash());
  LidarNerfModel model(test::runtime(), c, float(scene.norm.scale), 512);
  const field::HashGridConfig& g =
      dynamic_cast<const field::HashGridEncoder&>(model.encoder()).grid().config();
  CHECK_FALSE(g.deterministic);
  CHECK(g.half_table);
  CHECK(g.schedule == "per_point");
  CHECK(g.levels == 6);
  CHECK(model.levels() == 6);
  const FieldOptimizer optim(model, c);
  CHECK(optim.config().weight_decay == 1e-3f);
  CHECK(optim.config().beta2 == 0.95f);
}
