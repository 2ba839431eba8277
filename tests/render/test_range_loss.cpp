// Range loss and patch gradient loss: device vs reference, masks, deterministic reduction, and
// the gradients against finite differences of the double-precision reference.
#include <catch2/catch.hpp>

#include "render/range_loss.hpp"
#include "render_reference.hpp"
#include "render_test_data.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {
const float kScale = 0.0125f;

// Targets: range in (0.05, 0.9), intensity in (0, 1), label 1 for about 3 rays in 4.
std::vector<float> make_target(int n, uint64_t seed) {
  const auto u = test::make_uniform(3 * size_t(n), 0.f, 1.f, seed);
  std::vector<float> t(3 * size_t(n));
  for (int r = 0; r < n; ++r) {
    const float label = u[3 * r + 2] < 0.75f ? 1.f : 0.f;
    t[3 * r] = label * (0.05f + 0.85f * u[3 * r]);
    t[3 * r + 1] = label * u[3 * r + 1];
    t[3 * r + 2] = label;
  }
  return t;
}

template <typename F>
std::vector<float> central_diff(std::vector<double>& v, F loss) {
  std::vector<float> g(v.size());
  for (size_t i = 0; i < v.size(); ++i) {
    const double keep = v[i], eps = 1e-6;
    v[i] = keep + eps;
    const double lp = loss();
    v[i] = keep - eps;
    const double lm = loss();
    v[i] = keep;
    g[i] = float((lp - lm) / (2 * eps));
  }
  return g;
}
}  // namespace

TEST_CASE("Range loss equals the reference, masks dropped rays and reduces deterministically",
          "[render][loss]") {
  auto& rt = test::runtime();
  const auto cfg = render::RenderConfig::preset("nuscenes");
  render::RangeLoss rl(rt, cfg, kScale);
  for (int n : {1, 100, 1000, 4099}) {
    const auto target = make_target(n, 10 + n);
    const auto out = test::make_uniform(3 * size_t(n), 0.f, 1.f, 20 + n);
    auto bout = cl::Buffer::from(rt, out), btar = cl::Buffer::from(rt, target);
    cl::Buffer grad(rt, 3 * size_t(n) * 4), terms(rt, 3 * size_t(n) * 4),
        loss(rt, render::kLossFloats * 4);
    loss.fill_zero();
    rl.range(bout, btar, n, grad, terms, loss).wait();
    const auto values = render::RangeLoss::read_losses(loss);
    const auto dev_grad = grad.read_vec<float>(3 * size_t(n));
    std::vector<float> ref_grad;
    const auto ref = test::ref_range_loss<float>(n, 1000.f, 4.5f, 100.f, out, target, ref_grad);
    INFO("n = " << n);
    CHECK(values.depth == Approx(ref[0]).epsilon(1e-5));
    CHECK(values.ret == Approx(ref[1]).epsilon(1e-5));
    CHECK(values.intensity == Approx(ref[2]).epsilon(1e-5));
    CHECK(values.grad == 0.f);
    CHECK(test::max_sym_rel_err(dev_grad, ref_grad, 1e-12) < 1e-6);
    for (int r = 0; r < n; ++r)
      if (target[3 * r + 2] == 0.f) {
        REQUIRE(dev_grad[3 * r] == 0.f);
        REQUIRE(dev_grad[3 * r + 2] == 0.f);
        REQUIRE(dev_grad[3 * r + 1] != 0.f);  // the return head learns the drop
      }
    rl.range(bout, btar, n, grad, terms, loss).wait();
    const auto again = render::RangeLoss::read_losses(loss);
    CHECK(again.total() == values.total());  // bit-identical
  }
}

TEST_CASE("Range loss gradient matches finite differences", "[render][loss]") {
  auto& rt = test::runtime();
  const auto cfg = render::RenderConfig::preset("kitti360");
  render::RangeLoss rl(rt, cfg, kScale);
  const int n = 64;
  const auto target = make_target(n, 3);
  const auto out = test::make_uniform(3 * size_t(n), 0.f, 1.f, 4);
  auto bout = cl::Buffer::from(rt, out), btar = cl::Buffer::from(rt, target);
  cl::Buffer grad(rt, 3 * n * 4), terms(rt, 3 * n * 4), loss(rt, 16);
  rl.range(bout, btar, n, grad, terms, loss).wait();
  const auto dev = grad.read_vec<float>(3 * n);
  std::vector<double> od(out.begin(), out.end());
  const std::vector<double> td(target.begin(), target.end());
  const auto fd = central_diff(od, [&]() {
    std::vector<double> g;
    const auto l = test::ref_range_loss<double>(n, 1000, 1, 10, od, td, g);
    return l[0] + l[1] + l[2];
  });
  CHECK(test::max_sym_rel_err(dev, fd, 1e-6) < 1e-4);
}

TEST_CASE("Range loss with ray-drop label smoothing equals the reference and finite differences",
          "[render][loss]") {
  auto& rt = test::runtime();
  const auto cfg = render::RenderConfig::preset("kitti360");
  const int n = 257;
  const auto target = make_target(n, 31);
  const auto out = test::make_uniform(3 * size_t(n), 0.f, 1.f, 32);
  auto bout = cl::Buffer::from(rt, out), btar = cl::Buffer::from(rt, target);
  cl::Buffer grad(rt, 3 * n * 4), terms(rt, 3 * n * 4), loss(rt, 16);
  render::RangeLoss plain(rt, cfg, kScale);
  plain.range(bout, btar, n, grad, terms, loss).wait();
  const auto plain_values = render::RangeLoss::read_losses(loss);
  const auto plain_grad = grad.read_vec<float>(3 * n);

  render::RangeLoss smooth(rt, cfg, kScale, 0.2f);
  CHECK(smooth.label_smoothing() == 0.2f);
  smooth.range(bout, btar, n, grad, terms, loss).wait();
  const auto values = render::RangeLoss::read_losses(loss);
  const auto dev = grad.read_vec<float>(3 * n);
  std::vector<float> ref_grad;
  const auto ref = test::ref_range_loss<float>(n, 1000.f, 1.f, 10.f, out, target, ref_grad, 0.2f);
  CHECK(values.ret == Approx(ref[1]).epsilon(1e-5));
  CHECK(test::max_sym_rel_err(dev, ref_grad, 1e-12) < 1e-6);
  // Only the return term moves: its targets are 0.2 and 0.8 instead of 0 and 1.
  CHECK(values.depth == plain_values.depth);
  CHECK(values.intensity == plain_values.intensity);
  CHECK(values.ret != plain_values.ret);
  for (int r = 0; r < n; ++r) {
    REQUIRE(dev[3 * r] == plain_grad[3 * r]);
    REQUIRE(dev[3 * r + 2] == plain_grad[3 * r + 2]);
    const float label = target[3 * r + 2] > 0.5f ? 0.8f : 0.2f;
    REQUIRE(dev[3 * r + 1] == Approx(2.f * (out[3 * r + 1] - label) / n).epsilon(1e-5));
  }
  // The return term alone against finite differences (the other columns equal the unsmoothed
  // loss's, tested above): the device's targets are 0.2f and 0.8f, so the reference uses those
  // constants.
  std::vector<double> od(out.begin(), out.end());
  const std::vector<double> td(target.begin(), target.end());
  const auto fd = central_diff(od, [&]() {
    std::vector<double> g;
    return test::ref_range_loss<double>(n, 1000, 1, 10, od, td, g, double(0.2f))[1];
  });
  std::vector<float> dev_ret, fd_ret;
  for (int r = 0; r < n; ++r) {
    dev_ret.push_back(dev[3 * r + 1]);
    fd_ret.push_back(fd[3 * r + 1]);
  }
  CHECK(test::max_sym_rel_err(dev_ret, fd_ret, 1e-6) < 1e-4);
  CHECK_THROWS(render::RangeLoss(rt, cfg, kScale, 0.5f));
  CHECK_THROWS(render::RangeLoss(rt, cfg, kScale, -0.1f));
}

TEST_CASE(
    "Patch gradient loss (L1 and L2, rectangular patches) equals the reference and "
    "finite differences",
    "[render][loss]") {
  auto& rt = test::runtime();
  for (const bool l1 : {true, false}) {
    auto cfg = render::RenderConfig::preset("kitti360");
    cfg.patch_rows = l1 ? 2 : 3;
    cfg.patch_cols = l1 ? 8 : 5;
    cfg.grad_l1 = l1;
    cfg.grad_clip_m = 0.5f;  // metres: some pairs are masked by the clip, most are kept
    render::RangeLoss rl(rt, cfg, kScale);
    const int R = cfg.patch_rows, C = cfg.patch_cols, n_patches = 5, n = n_patches * R * C;
    // A smooth GT ramp per patch (steps of 0.2-0.4 m) with drops; predictions near it.
    std::vector<float> target(3 * n), out(3 * n);
    const auto u = test::make_uniform(4 * size_t(n), 0.f, 1.f, l1 ? 7 : 8);
    for (int r = 0; r < n; ++r) {
      const int q = r % (R * C), row = q / C, col = q % C;
      const float label = u[4 * r] < 0.85f ? 1.f : 0.f;
      target[3 * r] = label * (10.f + 0.3f * col + 0.2f * row + 0.1f * u[4 * r + 1]) * kScale;
      target[3 * r + 1] = label * 0.5f;
      target[3 * r + 2] = label;
      out[3 * r] = (10.f + 0.3f * col + 0.2f * row + 0.4f * (u[4 * r + 2] - 0.5f)) * kScale;
      out[3 * r + 1] = u[4 * r + 3];
      out[3 * r + 2] = 0.4f;
    }
    auto bout = cl::Buffer::from(rt, out), btar = cl::Buffer::from(rt, target);
    cl::Buffer grad(rt, 3 * n * 4), terms3(rt, 3 * n * 4), terms(rt, n * 4), loss(rt, 16);
    rl.range(bout, btar, n, grad, terms3, loss);
    rl.patch_gradient(bout, btar, n_patches, grad, terms, loss).wait();
    const auto values = render::RangeLoss::read_losses(loss);
    const auto dev = grad.read_vec<float>(3 * n);

    std::vector<float> range_only;
    test::ref_range_loss<float>(n, 1000.f, 1.f, 10.f, out, target, range_only);
    std::vector<float> ref_grad = range_only;
    const float ref_loss = test::ref_patch_grad_loss<float>(
        n_patches, R, C, l1, 100.f, 1.f / kScale, 0.5f, out, target, ref_grad);
    INFO("l1 = " << l1);
    REQUIRE(ref_loss > 0.f);
    CHECK(values.grad == Approx(ref_loss).epsilon(1e-5));
    CHECK(test::max_sym_rel_err(dev, ref_grad, 1e-9) < 1e-4);

    // Finite differences of the patch term alone (the range term's gradient subtracted).
    std::vector<float> dev_patch(n), fd_patch(n);
    std::vector<double> od(out.begin(), out.end());
    const std::vector<double> td(target.begin(), target.end());
    const auto fd = central_diff(od, [&]() {
      std::vector<double> g(3 * size_t(n), 0.0);
      return test::ref_patch_grad_loss<double>(n_patches, R, C, l1, 100, 1.0 / kScale, 0.5, od, td,
                                               g);
    });
    for (int r = 0; r < n; ++r) {
      dev_patch[r] = dev[3 * r] - range_only[3 * r];
      fd_patch[r] = fd[3 * r];
    }
    CHECK(test::max_sym_rel_err(dev_patch, fd_patch, 1e-3) < 2e-3);
    // Masked pairs exist (the clip and the drops): some rays get no patch gradient at all.
    size_t zero = 0;
    for (float g : fd_patch) zero += g == 0.f;
    CHECK(zero > 0);
  }
}
