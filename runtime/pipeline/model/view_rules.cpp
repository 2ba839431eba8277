// mix_variance_threshold / apply_mix_depth / drop_out_of_range (see view_rules.hpp).
#include "pipeline/model/view_rules.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"

namespace sgnlf::pipeline {

double mix_variance_threshold(const std::vector<float>& variance_m2, double factor) {
  require(!variance_m2.empty(), "mix_variance_threshold: an empty frame");
  std::vector<float> var = variance_m2;
  std::nth_element(var.begin(), var.begin() + long(var.size() / 2), var.end());
  return factor * double(var[var.size() / 2]);
}

size_t apply_mix_depth(RangeImage& img, const DepthStats& stats, double factor) {
  require(stats.median_m.size() == img.size() && stats.variance_m2.size() == img.size(),
          "apply_mix_depth: depth statistics for " + std::to_string(stats.median_m.size()) +
              " pixels, image of " + std::to_string(img.size()));
  const double threshold = mix_variance_threshold(stats.variance_m2, factor);
  size_t mixed = 0;
  for (size_t p = 0; p < img.size(); ++p)
    if (double(stats.variance_m2[p]) > threshold) img.range[p] = stats.median_m[p], ++mixed;
  return mixed;
}

size_t drop_out_of_range(RangeImage& img, const Sensor& sensor) {
  size_t dropped = 0;
  for (size_t p = 0; p < img.size(); ++p)
    if (img.ray_drop[p] > 0.5f && !sensor.in_range(double(img.range[p])))
      img.ray_drop[p] = 0.0f, ++dropped;
  return dropped;
}

}  // namespace sgnlf::pipeline
