// SSIM (scikit-image default, see ssim.hpp) with separable 7-tap box sums over the pixels that
// survive the border crop.
#include "metrics/ssim.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace sgnlf::metrics {
namespace {

// Horizontal 7-tap sums of `a` for every row and every column c ∈ [pad, width − pad).
std::vector<double> row_sums(const std::vector<double>& a, int height, int width) {
  const int pad = kSsimWindow / 2, out_w = width - 2 * pad;
  std::vector<double> out(size_t(height) * out_w);
  for (int r = 0; r < height; ++r)
    for (int c = 0; c < out_w; ++c) {
      double s = 0.0;
      for (int k = 0; k < kSsimWindow; ++k) s += a[size_t(r) * width + c + k];
      out[size_t(r) * out_w + c] = s;
    }
  return out;
}

// Window means (box sums / 49) at the cropped pixels, row-major (height−6)×(width−6).
std::vector<double> window_means(const std::vector<double>& a, int height, int width) {
  const int pad = kSsimWindow / 2, out_w = width - 2 * pad, out_h = height - 2 * pad;
  const std::vector<double> rs = row_sums(a, height, width);
  std::vector<double> out(size_t(out_h) * out_w);
  const double inv_np = 1.0 / (kSsimWindow * kSsimWindow);
  for (int r = 0; r < out_h; ++r)
    for (int c = 0; c < out_w; ++c) {
      double s = 0.0;
      for (int k = 0; k < kSsimWindow; ++k) s += rs[size_t(r + k) * out_w + c];
      out[size_t(r) * out_w + c] = s * inv_np;
    }
  return out;
}

}  // namespace

double ssim(const std::vector<double>& im1, const std::vector<double>& im2, int height,
            int width, double data_range) {
  const size_t n = size_t(height) * size_t(width);
  require(height >= kSsimWindow && width >= kSsimWindow,
          "ssim: image " + std::to_string(height) + "x" + std::to_string(width) +
              " is smaller than the 7x7 window");
  require(im1.size() == n && im2.size() == n,
          "ssim: image sizes " + std::to_string(im1.size()) + " and " +
              std::to_string(im2.size()) + " do not match " + std::to_string(height) + "x" +
              std::to_string(width));
  require(std::isfinite(data_range) && data_range > 0.0,
          "ssim: data_range must be > 0 (constant ground truth?), got " +
              std::to_string(data_range));
  std::vector<double> xx(n), yy(n), xy(n);
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(im1[i]) || !std::isfinite(im2[i]))
      throw Error("ssim: non-finite pixel at index " + std::to_string(i));
    xx[i] = im1[i] * im1[i];
    yy[i] = im2[i] * im2[i];
    xy[i] = im1[i] * im2[i];
  }
  const auto ux = window_means(im1, height, width), uy = window_means(im2, height, width);
  const auto uxx = window_means(xx, height, width), uyy = window_means(yy, height, width);
  const auto uxy = window_means(xy, height, width);

  const double np = kSsimWindow * kSsimWindow;
  const double cov_norm = np / (np - 1.0);  // use_sample_covariance=True
  const double c1 = std::pow(0.01 * data_range, 2), c2 = std::pow(0.03 * data_range, 2);
  double sum = 0.0;
  for (size_t i = 0; i < ux.size(); ++i) {
    const double vx = cov_norm * (uxx[i] - ux[i] * ux[i]);
    const double vy = cov_norm * (uyy[i] - uy[i] * uy[i]);
    const double vxy = cov_norm * (uxy[i] - ux[i] * uy[i]);
    const double a1 = 2.0 * ux[i] * uy[i] + c1, a2 = 2.0 * vxy + c2;
    const double b1 = ux[i] * ux[i] + uy[i] * uy[i] + c1, b2 = vx + vy + c2;
    sum += (a1 * a2) / (b1 * b2);
  }
  return sum / double(ux.size());
}

}  // namespace sgnlf::metrics
