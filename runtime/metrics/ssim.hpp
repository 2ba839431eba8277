// SSIM exactly as scikit-image's `structural_similarity(im1, im2, data_range=R)` with its
// defaults, which is how the peers call it (LiDAR4D and GeoNLF utils/metrics.py:
// `structural_similarity(pred, gt, data_range=np.max(gt) - np.min(gt))` on the clipped H×W
// depth or intensity image; protocol §4):
//   7×7 uniform window (gaussian_weights=False), use_sample_covariance=True (49/48),
//   K1 = 0.01, K2 = 0.03, C1 = (K1·R)², C2 = (K2·R)²,
//   S = (2·μx·μy + C1)(2·σxy + C2) / ((μx² + μy² + C1)(σx² + σy² + C2)),
//   mean of S over the image with the (7−1)/2 = 3-pixel border cropped.
// The window never reaches past the image for the cropped pixels, so scipy's reflect padding
// does not enter the result. We compute in double; scikit-image computes in the input's
// float type (float32 for the peers' arrays), so theirs differs from ours by float32 rounding
// only (not measured here: no Python/scikit-image on the build machine).
#pragma once
#include <vector>

namespace sgnlf::metrics {

constexpr int kSsimWindow = 7;

// Row-major height×width images of equal size; needs height, width ≥ 7 and data_range > 0
// (a constant ground truth has no SSIM: scikit-image returns NaN there; we throw).
double ssim(const std::vector<double>& im1, const std::vector<double>& im2, int height,
            int width, double data_range);

}  // namespace sgnlf::metrics
