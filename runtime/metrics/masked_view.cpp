// mask_view / to_points_lidar (see masked_view.hpp).
#include "metrics/masked_view.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "metrics/image_metrics.hpp"

namespace sgnlf::metrics {
namespace {

void check_image(const Sensor& s, const RangeImage& img, const std::string& who,
                 const char* which) {
  const size_t n = size_t(s.height) * s.width;
  require(img.height == s.height && img.width == s.width,
          who + ": " + which + " image is " + std::to_string(img.height) + "x" +
              std::to_string(img.width) + ", sensor '" + s.name + "' is " +
              std::to_string(s.height) + "x" + std::to_string(s.width));
  require(img.range.size() == n && img.intensity.size() == n && img.ray_drop.size() == n,
          who + ": " + which + " channels have " + std::to_string(img.range.size()) + "/" +
              std::to_string(img.intensity.size()) + "/" + std::to_string(img.ray_drop.size()) +
              " pixels (range/intensity/ray_drop), expected " + std::to_string(n));
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(img.range[i]) || !std::isfinite(img.intensity[i]) ||
        !std::isfinite(img.ray_drop[i]))
      throw Error(who + ": " + which + " image has a non-finite value at pixel " +
                  std::to_string(i));
}

}  // namespace

MaskedView mask_view(const Sensor& sensor, const RangeImage& pred, const RangeImage& gt,
                     const char* who) {
  check_image(sensor, pred, who, "predicted");
  check_image(sensor, gt, who, "ground-truth");
  const size_t n = pred.size();
  MaskedView v;
  v.depth.resize(n);
  v.intensity.resize(n);
  v.gt_depth.resize(n);
  v.gt_intensity.resize(n);
  // LiDAR4D's eval_step: gt depth and intensity are multiplied by the gt label, the prediction
  // by its own mask (probability > 0.5).
  for (size_t i = 0; i < n; ++i) {
    const float mask = pred.ray_drop[i] > float(kRaydropThreshold) ? 1.f : 0.f;
    v.depth[i] = pred.range[i] * mask;
    v.intensity[i] = pred.intensity[i] * mask;
    v.gt_depth[i] = gt.range[i] * gt.ray_drop[i];
    v.gt_intensity[i] = gt.intensity[i] * gt.ray_drop[i];
  }
  return v;
}

std::vector<geometry::Point3f> to_points_lidar(const Sensor& s, const std::vector<float>& range,
                                               std::vector<uint32_t>* pixels) {
  std::vector<geometry::Point3f> pts;
  if (pixels) pixels->clear();
  for (int r = 0; r < s.height; ++r)
    for (int c = 0; c < s.width; ++c) {
      const size_t i = size_t(r) * s.width + c;
      const float d = range[i];
      if (d == 0.f) continue;
      pts.push_back(pixel_direction(s, r, c) * d);
      if (pixels) pixels->push_back(uint32_t(i));
    }
  return pts;
}

}  // namespace sgnlf::metrics
