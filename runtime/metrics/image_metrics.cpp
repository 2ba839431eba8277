// Depth, intensity and ray-drop metrics of one view (protocol §4; see image_metrics.hpp).
#include "metrics/image_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "metrics/ssim.hpp"

namespace sgnlf::metrics {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void check_inputs(const char* what, const std::vector<float>& pred, const std::vector<float>& gt,
                  size_t n) {
  require(pred.size() == n && gt.size() == n,
          std::string(what) + ": pred has " + std::to_string(pred.size()) + " pixels, gt " +
              std::to_string(gt.size()) + ", expected " + std::to_string(n));
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(pred[i]) || !std::isfinite(gt[i]))
      throw Error(std::string(what) + ": non-finite value at pixel " + std::to_string(i) +
                " (pred " + std::to_string(pred[i]) + ", gt " + std::to_string(gt[i]) + ")");
}

std::vector<double> clipped(const std::vector<float>& v, double lo, double hi) {
  std::vector<double> out(v.size());
  for (size_t i = 0; i < v.size(); ++i) out[i] = std::clamp(double(v[i]), lo, hi);
  return out;
}

// RMSE, MedAE, SSIM, PSNR (peak²/MSE) shared by depth and intensity.
template <typename M>
M common_metrics(const std::vector<double>& p, const std::vector<double>& g, int h, int w,
                 double peak) {
  M m;
  double se = 0.0;
  std::vector<double> ae(p.size());
  for (size_t i = 0; i < p.size(); ++i) {
    const double d = g[i] - p[i];
    se += d * d;
    ae[i] = std::abs(d);
  }
  const double mse = se / double(p.size());
  m.rmse = std::sqrt(mse);
  m.medae = median(std::move(ae));
  const auto [gmin, gmax] = std::minmax_element(g.begin(), g.end());
  m.ssim = ssim(p, g, h, w, *gmax - *gmin);
  m.psnr = mse > 0.0 ? 10.0 * std::log10(peak * peak / mse) : kNaN;
  return m;
}

}  // namespace

double median(std::vector<double> v) {
  require(!v.empty(), "median: empty input");
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  const double upper = v[mid];
  if (v.size() % 2 == 1) return upper;
  const double lower = *std::max_element(v.begin(), v.begin() + mid);
  return 0.5 * (lower + upper);
}

DepthMetrics depth_metrics(const std::vector<float>& pred, const std::vector<float>& gt,
                           int height, int width) {
  check_inputs("depth_metrics", pred, gt, size_t(height) * width);
  const auto p = clipped(pred, kDepthMin, kDepthMax), g = clipped(gt, kDepthMin, kDepthMax);
  auto m = common_metrics<DepthMetrics>(p, g, height, width, kDepthMax);
  size_t good = 0;
  for (size_t i = 0; i < p.size(); ++i)
    if (std::max(g[i] / p[i], p[i] / g[i]) < kDelta1) ++good;
  m.delta1 = double(good) / double(p.size());
  return m;
}

IntensityMetrics intensity_metrics(const std::vector<float>& pred, const std::vector<float>& gt,
                                   int height, int width) {
  check_inputs("intensity_metrics", pred, gt, size_t(height) * width);
  const auto p = clipped(pred, kIntensityMin, kIntensityMax);
  const auto g = clipped(gt, kIntensityMin, kIntensityMax);
  return common_metrics<IntensityMetrics>(p, g, height, width, kIntensityMax);
}

DepthErrorParts depth_error_parts(const std::vector<float>& pred, const std::vector<float>& gt,
                                  const std::vector<float>& prob, const std::vector<float>& label) {
  require(!gt.empty(), "depth_error_parts: empty image");
  check_inputs("depth_error_parts", pred, gt, gt.size());
  check_inputs("depth_error_parts", prob, label, gt.size());
  double se[3] = {0.0, 0.0, 0.0};  // returns, missed, false
  size_t missed = 0, false_return = 0;
  for (size_t i = 0; i < gt.size(); ++i) {
    const double e = depth_sq_error(pred[i], gt[i]);
    switch (return_case(prob[i], label[i])) {
      case ReturnCase::both: se[0] += e; break;
      case ReturnCase::missed: se[1] += e, ++missed; break;
      case ReturnCase::false_return: se[2] += e, ++false_return; break;
      // Both dropped: both sides are masked to 0, clipped alike, and contribute nothing.
      case ReturnCase::neither: break;
    }
  }
  const double n = double(gt.size());
  return {se[0] / n, se[1] / n, se[2] / n, double(missed) / n, double(false_return) / n};
}

RaydropMetrics raydrop_metrics(const std::vector<float>& prob, const std::vector<float>& label) {
  check_inputs("raydrop_metrics", prob, label, label.size());
  require(!label.empty(), "raydrop_metrics: empty image");
  double se = 0.0;
  size_t tp = 0, fp = 0, tn = 0, fn = 0;
  for (size_t i = 0; i < label.size(); ++i) {
    if (label[i] != 0.f && label[i] != 1.f)
      throw Error("raydrop_metrics: label at pixel " + std::to_string(i) + " is " +
                std::to_string(label[i]) + ", expected 0 or 1");
    const double d = double(label[i]) - double(prob[i]);
    se += d * d;
    const bool hit = double(prob[i]) > kRaydropThreshold, truth = label[i] == 1.f;
    tp += hit && truth;
    fp += hit && !truth;
    tn += !hit && !truth;
    fn += !hit && truth;
  }
  RaydropMetrics m;
  const double n = double(label.size());
  m.rmse = std::sqrt(se / n);
  m.acc = double(tp + tn) / n;
  // precision = TP/(TP+FP), recall = TP/(TP+FN), F1 = 2PR/(P+R); NaN where numpy's is.
  const double precision = tp + fp > 0 ? double(tp) / double(tp + fp) : kNaN;
  const double recall = tp + fn > 0 ? double(tp) / double(tp + fn) : kNaN;
  m.f1 = precision + recall > 0.0 ? 2.0 * precision * recall / (precision + recall) : kNaN;
  return m;
}

}  // namespace sgnlf::metrics
