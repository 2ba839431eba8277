// One test view as every view metric sees it (protocol §4, LiDAR4D's eval_step): the prediction
// multiplied by its return mask (probability > 0.5), the ground truth by its return label, and
// the masked images unprojected to points in the LiDAR frame. Shared by evaluate_view and the
// error anatomy (anatomy.hpp), so both score the same pixels and points.
#pragma once
#include <cstdint>
#include <vector>

#include "geometry/kdtree.hpp"
#include "geometry/range_image.hpp"
#include "geometry/sensor.hpp"

namespace sgnlf::metrics {

struct MaskedView {
  std::vector<float> depth, intensity;        // prediction × (probability > 0.5), row-major H×W
  std::vector<float> gt_depth, gt_intensity;  // ground truth × label
};

// Checks both images against the sensor's size and for non-finite values (Error naming `who`,
// which image, the sizes or the pixel), then masks them.
MaskedView mask_view(const Sensor& sensor, const RangeImage& pred, const RangeImage& gt,
                     const char* who);

// Pixels with range ≠ 0 → points in the LiDAR frame (protocol §1; the peers' pano_to_lidar
// keeps every non-zero range), in row-major pixel order. With `pixels`, each point's pixel index.
std::vector<geometry::Point3f> to_points_lidar(const Sensor& s, const std::vector<float>& range,
                                               std::vector<uint32_t>* pixels = nullptr);

}  // namespace sgnlf::metrics
