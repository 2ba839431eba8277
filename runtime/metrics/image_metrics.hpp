// Per-pixel metrics of one rendered view against its ground truth (protocol §4), as the peers'
// DepthMeter / IntensityMeter / RaydropMeter compute them over all H×W pixels:
//   depth:     pred (already masked) and gt clipped to [1e-6, 80] m; RMSE, MedAE = median
//              |gt − pred|, SSIM (data_range = max(gt) − min(gt) after clipping),
//              PSNR = 10·log10(80² / MSE), δ1 = frac(max(gt/pred, pred/gt) < 1.25) (GeoNLF).
//   intensity: clipped to [1e-6, 1]; RMSE, MedAE, SSIM, PSNR = 10·log10(1 / MSE).
//   ray-drop:  RMSE(probability, label); accuracy and F1 of (probability > 0.5) vs label.
// Values that are undefined (PSNR of identical images, F1 without positives) are NaN; the
// JSON layer writes them as null.
#pragma once
#include <algorithm>
#include <vector>

namespace sgnlf::metrics {

constexpr double kDepthMin = 1e-6, kDepthMax = 80.0;          // m
constexpr double kIntensityMin = 1e-6, kIntensityMax = 1.0;
constexpr double kRaydropThreshold = 0.5;
constexpr double kDelta1 = 1.25;

struct DepthMetrics {
  double rmse = 0, medae = 0, ssim = 0, psnr = 0, delta1 = 0;
};
struct IntensityMetrics {
  double rmse = 0, medae = 0, ssim = 0, psnr = 0;
};
struct RaydropMetrics {
  double rmse = 0, acc = 0, f1 = 0;
};
// Where a view's depth MSE comes from (not in the peers' tables): the squared errors of the
// masked, clipped depth of depth_metrics split by the pixel's two return decisions, each summed
// and divided by all H×W pixels, so that returns + missed + false = depth_rmse² exactly.
//   returns: both return (range error);  missed: ground truth returns, predicted dropped
//   (≈ the ground-truth range²);  false: predicted return where the ground truth dropped.
// missed_frac / false_frac: those pixels' share of all pixels (1 − raydrop_acc together).
struct DepthErrorParts {
  double mse_returns = 0, mse_missed = 0, mse_false = 0, missed_frac = 0, false_frac = 0;
};

// One pixel's return decisions: the prediction's (probability > 0.5) against the label.
enum class ReturnCase { both, missed, false_return, neither };
inline ReturnCase return_case(float prob, float label) {
  const bool hit = double(prob) > kRaydropThreshold, truth = label == 1.f;
  return hit && truth ? ReturnCase::both
         : truth      ? ReturnCase::missed
         : hit        ? ReturnCase::false_return
                      : ReturnCase::neither;
}
// One pixel's squared depth error as depth_metrics and depth_error_parts count it: masked
// depths clipped to [kDepthMin, kDepthMax] m (0 when both are masked).
inline double depth_sq_error(float pred, float gt) {
  const double d = std::clamp(double(gt), kDepthMin, kDepthMax) -
                   std::clamp(double(pred), kDepthMin, kDepthMax);
  return d * d;
}

// Median as numpy: the mean of the two middle values for an even count.
double median(std::vector<double> v);

// `pred` must already be multiplied by the predicted return mask; all images row-major H×W.
DepthMetrics depth_metrics(const std::vector<float>& pred, const std::vector<float>& gt,
                           int height, int width);
IntensityMetrics intensity_metrics(const std::vector<float>& pred, const std::vector<float>& gt,
                                   int height, int width);
// `pred` / `gt` as depth_metrics takes them, `prob` / `label` as raydrop_metrics.
DepthErrorParts depth_error_parts(const std::vector<float>& pred, const std::vector<float>& gt,
                                  const std::vector<float>& prob, const std::vector<float>& label);
// `prob` = predicted return probability, `label` = ground-truth return label (0 or 1).
RaydropMetrics raydrop_metrics(const std::vector<float>& prob, const std::vector<float>& label);

}  // namespace sgnlf::metrics
