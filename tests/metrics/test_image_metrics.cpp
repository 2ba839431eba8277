// Depth, intensity and ray-drop metrics on cases computed by hand (protocol §4).
#include <catch2/catch.hpp>

#include <cmath>

#include "core/error.hpp"
#include "metrics/image_metrics.hpp"
#include "metrics/ssim.hpp"

using namespace sgnlf;
using namespace sgnlf::metrics;

TEST_CASE("median follows numpy (mean of the middle pair for even counts)", "[metrics]") {
  CHECK(median({3.0, 1.0, 2.0}) == 2.0);
  CHECK(median({4.0, 1.0, 3.0, 2.0}) == 2.5);
  CHECK(median({5.0}) == 5.0);
  CHECK_THROWS_AS(median({}), Error);
}

TEST_CASE("depth metrics: clipping to [1e-6, 80], RMSE, MedAE, PSNR at 80 m, delta1",
          "[metrics][depth]") {
  const int h = 7, w = 8, n = h * w;
  std::vector<float> gt(n, 10.f), pred(n, 10.f);
  pred[0] = 12.f;    // error 2, ratio 1.2 < 1.25
  pred[1] = 0.f;     // masked-out pixel: clipped to 1e-6, error 10 − 1e-6
  pred[3] = 100.f;   // clipped to 80, error 70
  gt[55] = 0.f;      // no return in either: both 1e-6, error 0, ratio 1
  pred[55] = 0.f;
  const DepthMetrics m = depth_metrics(pred, gt, h, w);
  const double e1 = 10.0 - 1e-6;
  const double mse = (4.0 + e1 * e1 + 4900.0) / n;
  CHECK(m.rmse == Approx(std::sqrt(mse)).epsilon(1e-12));
  CHECK(m.psnr == Approx(10.0 * std::log10(6400.0 / mse)).epsilon(1e-12));
  CHECK(m.medae == 0.0);
  CHECK(m.delta1 == Approx(54.0 / 56.0).epsilon(1e-15));
  // SSIM is taken on the clipped images with data_range = max(gt) − min(gt) = 10 − 1e-6.
  std::vector<double> pc(n), gc(n);
  for (int i = 0; i < n; ++i) {
    pc[i] = std::min(std::max(double(pred[i]), 1e-6), 80.0);
    gc[i] = std::min(std::max(double(gt[i]), 1e-6), 80.0);
  }
  CHECK(m.ssim == Approx(ssim(pc, gc, h, w, 10.0 - 1e-6)).epsilon(1e-14));
  CHECK(m.ssim < 1.0);
}

TEST_CASE("depth metrics of a perfect prediction", "[metrics][depth]") {
  std::vector<float> gt(64);
  for (int i = 0; i < 64; ++i) gt[i] = 1.f + float(i % 9);
  const DepthMetrics m = depth_metrics(gt, gt, 8, 8);
  CHECK(m.rmse == 0.0);
  CHECK(std::isnan(m.psnr));  // 10·log10(80²/0) is undefined: written as null
  CHECK(m.ssim == Approx(1.0));
  CHECK(m.delta1 == 1.0);
}

TEST_CASE("intensity metrics: clipping to [1e-6, 1], PSNR at peak 1", "[metrics][intensity]") {
  const int h = 7, w = 7, n = h * w;
  std::vector<float> gt(n, 0.5f), pred(n, 0.5f);
  pred[0] = 1.5f;   // → 1, error 0.5
  pred[1] = -0.2f;  // → 1e-6, error 0.5 − 1e-6
  pred[2] = 0.75f;  // error 0.25
  gt[48] = 0.f;
  pred[48] = 0.f;
  const IntensityMetrics m = intensity_metrics(pred, gt, h, w);
  const double e1 = 0.5 - 1e-6;
  const double mse = (0.25 + e1 * e1 + 0.0625) / n;
  CHECK(m.rmse == Approx(std::sqrt(mse)).epsilon(1e-12));
  CHECK(m.psnr == Approx(10.0 * std::log10(1.0 / mse)).epsilon(1e-12));
  CHECK(m.medae == 0.0);
  CHECK(m.ssim < 1.0);
  CHECK(m.ssim > 0.0);
}

TEST_CASE("ray-drop RMSE, accuracy and F1 at 0.5 (by hand)", "[metrics][raydrop]") {
  // hits (p > 0.5): 1 1 0 0 0 1 0 1 vs labels 1 1 1 0 0 0 0 1 → TP 3, FP 1, FN 1, TN 3.
  const std::vector<float> prob = {0.9f, 0.6f, 0.4f, 0.1f, 0.5f, 0.7f, 0.2f, 1.0f};
  const std::vector<float> label = {1, 1, 1, 0, 0, 0, 0, 1};
  const RaydropMetrics m = raydrop_metrics(prob, label);
  CHECK(m.acc == 0.75);
  CHECK(m.f1 == Approx(0.75).epsilon(1e-15));
  // squared errors 0.01 0.16 0.36 0.01 0.25 0.49 0.04 0 → mean 0.165
  CHECK(m.rmse == Approx(std::sqrt(0.165)).epsilon(1e-6));
}

TEST_CASE("ray-drop F1 is undefined without positives; bad inputs throw", "[metrics][raydrop]") {
  const RaydropMetrics m = raydrop_metrics({0.1f, 0.2f}, {0.f, 0.f});
  CHECK(m.acc == 1.0);
  CHECK(std::isnan(m.f1));
  CHECK_THROWS_AS(raydrop_metrics({0.1f}, {0.f, 1.f}), Error);
  CHECK_THROWS_AS(raydrop_metrics({0.1f}, {0.5f}), Error);
  CHECK_THROWS_AS(raydrop_metrics({std::nanf("")}, {1.f}), Error);
  CHECK_THROWS_AS(depth_metrics(std::vector<float>(49, 1.f), std::vector<float>(48, 1.f), 7, 7),
                  Error);
}

TEST_CASE("depth error parts: returns, missed and false returns sum to the depth MSE",
          "[metrics][depth]") {
  const int h = 7, w = 8, n = h * w;  // SSIM's 7×7 window needs 7 rows
  // Ground truth: 10 m everywhere but pixels 2 and 3 (dropped); prediction masked as
  // evaluate_view masks it (probability > 0.5).
  std::vector<float> label(n, 1.f), prob(n, 0.9f), gt(n, 10.f), pred(n, 10.f);
  label[2] = label[3] = 0.f;
  gt[2] = gt[3] = 0.f;
  pred[0] = 11.f;                    // both return: error 1
  pred[1] = 100.f;                   // both return, clipped to 80: error 70
  prob[2] = 0.2f, pred[2] = 0.f;     // both dropped: nothing
  prob[3] = 0.7f, pred[3] = 30.f;    // false return: 30 − 1e-6
  prob[4] = 0.5f, pred[4] = 0.f;     // missed return (0.5 is not > 0.5): 10 − 1e-6
  prob[5] = 0.1f, pred[5] = 0.f;     // missed return
  const DepthErrorParts p = depth_error_parts(pred, gt, prob, label);
  const double e10 = 10.0 - 1e-6, e30 = 30.0 - 1e-6;
  CHECK(p.mse_returns == Approx((1.0 + 4900.0) / n).epsilon(1e-12));
  CHECK(p.mse_missed == Approx(2.0 * e10 * e10 / n).epsilon(1e-12));
  CHECK(p.mse_false == Approx(e30 * e30 / n).epsilon(1e-12));
  CHECK(p.missed_frac == Approx(2.0 / n));
  CHECK(p.false_frac == Approx(1.0 / n));
  const DepthMetrics m = depth_metrics(pred, gt, h, w);
  CHECK(p.mse_returns + p.mse_missed + p.mse_false == Approx(m.rmse * m.rmse).epsilon(1e-12));
  const RaydropMetrics r = raydrop_metrics(prob, label);
  CHECK(1.0 - p.missed_frac - p.false_frac == Approx(r.acc).epsilon(1e-12));
  CHECK_THROWS_AS(depth_error_parts(pred, gt, prob, std::vector<float>(n - 1, 1.f)), Error);
  CHECK_THROWS_AS(depth_error_parts({}, {}, {}, {}), Error);
}
