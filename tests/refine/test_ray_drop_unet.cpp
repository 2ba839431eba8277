// RayDropUNet on the device: the composed backward against finite differences of the device
// forward (odd sizes: the up stages pad), training on a synthetic ray-drop problem (BCE well
// below the input probability's, accuracy above thresholding it, on held-out frames too),
// bit-identical training and inference for a seed, refused configs and sizes.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "refine/ray_drop_training.hpp"
#include "refine/ray_drop_unet.hpp"
#include "support/test_device.hpp"
#include "synthetic_ray_drop.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {
refine::RayDropUNetConfig small_config() {
  refine::RayDropUNetConfig c;
  c.channels = 16;
  c.depth = 2;
  return c;
}
std::vector<float> infer(refine::RayDropUNet& net, const test::RayDropFrames& f) {
  auto& rt = test::runtime();
  const auto in = cl::Buffer::from(rt, f.inputs);
  cl::Buffer probs(rt, f.masks.size() * sizeof(float));
  net.forward(in, f.n, f.h, f.w, probs);
  return probs.read_all<float>();
}
}  // namespace

TEST_CASE("RayDropUNet gradients agree with finite differences of the device forward",
          "[refine][unet][fd]") {
  auto& rt = test::runtime();
  auto cfg = small_config();
  cfg.slope = 0.1f;  // leaky: fewer dead units, every layer's gradient is exercised
  refine::RayDropUNet net(rt, cfg);
  // 17 × 25: pooled to 8 × 12 and 4 × 6; the up stages pad 16 → 17 and 24 → 25.
  const auto f = test::synthetic_ray_drop(2, 17, 25, 5);
  const auto in = cl::Buffer::from(rt, f.inputs), masks = cl::Buffer::from(rt, f.masks);
  const auto no_boxes = cl::Buffer::from(rt, std::vector<int>(4, 0));
  cl::Buffer losses(rt, sizeof(float));
  const auto p0 = net.initial_params();
  net.step(in, masks, f.n, f.h, f.w, no_boxes, 0, 0, 0.0f, losses, 0);  // lr 0: params stay
  const auto grad = net.grad().read_all<float>();
  CHECK(net.params().read_all<float>() == p0);
  const double l0 = test::mean_bce(infer(net, f), f.masks);
  CHECK(std::fabs(losses.read_vec<float>(1)[0] - l0) < 1e-5);
  auto central = [&](size_t k, float h) {
    auto p = p0;
    p[k] = p0[k] + h;
    net.params().write_vec(p);
    const double lp = test::mean_bce(infer(net, f), f.masks);
    p[k] = p0[k] - h;
    net.params().write_vec(p);
    const double lm = test::mean_bce(infer(net, f), f.masks);
    return float((lp - lm) / (2.0 * h));
  };
  // Two steps per entry: float noise of the forward (~1e-8 in the mean loss) rules the small
  // one, the kinks of the leaky ReLUs and max pools that the large one may cross rule the
  // other; the entry's difference is the one closer to the analytic value. A mis-wired
  // backward (a lost skip gradient, an offset upsampling) is off at both.
  std::vector<float> fd, an;
  for (const auto& s : net.layout().slices()) {
    int taken = 0;
    for (size_t k = s.offset; k < s.offset + s.count && taken < 6; k += s.count / 7 + 1) {
      if (grad[k] == 0.0f && p0[k] == 0.0f) continue;  // padding columns of the logit conv
      const float a = central(k, 2.5e-4f), b = central(k, 1e-3f);
      fd.push_back(std::fabs(a - grad[k]) < std::fabs(b - grad[k]) ? a : b);
      an.push_back(grad[k]);
      ++taken;
    }
  }
  net.params().write_vec(p0);
  REQUIRE(fd.size() > 40);
  double scale = 0;
  for (float g : an) scale = std::max(scale, double(std::fabs(g)));
  const double err = test::max_sym_rel_err(fd, an, 0.02 * scale);
  std::printf("RayDropUNet FD: %zu entries, max |g| %.3g, max sym rel err %.3g\n", fd.size(),
              scale, err);
  int bad = 0;
  for (size_t i = 0; i < fd.size(); ++i)
    if (std::fabs(fd[i] - an[i]) > 5e-5 + 0.02 * std::fabs(an[i])) {
      std::printf("  entry %zu: fd %.5g, analytic %.5g\n", i, fd[i], an[i]);
      ++bad;
    }
  CHECK(bad == 0);
  CHECK(err < 5e-2);
}

TEST_CASE("RayDropUNet training beats the input probability on a synthetic ray-drop problem",
          "[refine][unet][train]") {
  auto& rt = test::runtime();
  auto cfg = small_config();
  cfg.steps = 100;
  cfg.lr = 5e-3f;
  refine::RayDropUNet net(rt, cfg);
  const auto f = test::synthetic_ray_drop(3, 16, 64, 11);
  const auto in = cl::Buffer::from(rt, f.inputs), masks = cl::Buffer::from(rt, f.masks);
  const auto r = refine::train_ray_drop(net, in, masks, f.n, f.h, f.w);
  const auto p_in = test::input_probability(f);
  const double bce_in = test::mean_bce(p_in, f.masks), acc_in = test::accuracy(p_in, f.masks);
  const auto p = infer(net, f);
  const double bce = test::mean_bce(p, f.masks), acc = test::accuracy(p, f.masks);
  // Held-out frames of the same kind (the pipeline applies it to test frames).
  const auto g = test::synthetic_ray_drop(2, 16, 64, 12);
  const auto pg_in = test::input_probability(g), pg = infer(net, g);
  const double acc_g_in = test::accuracy(pg_in, g.masks), acc_g = test::accuracy(pg, g.masks);
  std::printf("RayDropUNet train: BCE %.4f -> %.4f (input %.4f), acc %.4f (input %.4f), "
              "held-out acc %.4f (input %.4f), boxes %d\n",
              r.initial_loss, r.final_loss, bce_in, acc, acc_in, acc_g, acc_g_in, r.boxes);
  REQUIRE(r.loss.size() == size_t(cfg.steps));
  CHECK(r.boxes > cfg.steps * 10);
  CHECK(std::fabs(r.final_loss - bce) < 1e-4);  // the routine's summary is the inference BCE
  CHECK(r.final_loss < 0.5 * bce_in);
  CHECK(acc > acc_in + 0.05);
  CHECK(acc_g > acc_g_in + 0.03);
}

TEST_CASE("RayDropUNet training and inference are bit-identical for a seed",
          "[refine][unet][determinism]") {
  auto& rt = test::runtime();
  auto cfg = small_config();
  cfg.steps = 12;
  cfg.lr = 5e-3f;
  const auto f = test::synthetic_ray_drop(2, 16, 32, 21);
  const auto in = cl::Buffer::from(rt, f.inputs), masks = cl::Buffer::from(rt, f.masks);
  refine::RayDropUNet a(rt, cfg), b(rt, cfg);
  const auto ra = refine::train_ray_drop(a, in, masks, f.n, f.h, f.w);
  const auto rb = refine::train_ray_drop(b, in, masks, f.n, f.h, f.w);
  CHECK(ra.loss == rb.loss);
  CHECK(a.params().read_all<float>() == b.params().read_all<float>());
  const auto pa = infer(a, f);
  CHECK(pa == infer(a, f));  // inference twice: identical
  CHECK(pa == infer(b, f));
  // reset() restarts from the same initial state; reporting progress (the queue waited for
  // every 10 steps) changes nothing.
  a.reset();
  std::vector<int> reported;
  CHECK(refine::train_ray_drop(a, in, masks, f.n, f.h, f.w,
                               [&](int done) { reported.push_back(done); })
            .loss == ra.loss);
  CHECK(reported == std::vector<int>{10, 12});
  // Another seed: other weights and boxes, other losses.
  cfg.seed = 2;
  refine::RayDropUNet c(rt, cfg);
  CHECK(refine::train_ray_drop(c, in, masks, f.n, f.h, f.w).loss != ra.loss);
}

TEST_CASE("RayDropUNet refuses bad configs and images too small for its depth",
          "[refine][unet]") {
  auto& rt = test::runtime();
  auto bad = small_config();
  bad.channels = 24;
  REQUIRE_THROWS_WITH(refine::RayDropUNet(rt, bad), Catch::Contains("'channels' = 24"));
  bad = small_config();
  bad.slope = -0.5f;
  REQUIRE_THROWS_WITH(refine::RayDropUNet(rt, bad), Catch::Contains("'slope'"));
  refine::RayDropUNet net(rt, small_config());
  cl::Buffer b(rt, 4096);
  REQUIRE_THROWS_WITH(net.forward(b, 1, 3, 16, b), Catch::Contains("cannot be pooled 2 times"));
  REQUIRE_THROWS_WITH(net.forward(b, 0, 8, 8, b), Catch::Contains("n = 0"));
  REQUIRE_THROWS_WITH(net.forward(b, 2, 16, 16, b), Catch::Contains("'in'"));
}
