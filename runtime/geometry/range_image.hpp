// Range images and the projection both ways, exactly as protocol §1 (the peers' pixel
// conventions: no half-pixel offset, nearest return per pixel, points at ≥ max range dropped).
#pragma once
#include <Eigen/Core>
#include <vector>

#include "geometry/sensor.hpp"

namespace sgnlf {

// Row-major H×W channels. range 0 = no return. `ray_drop` is the return label (1 = return).
struct RangeImage {
  int height = 0, width = 0;
  std::vector<float> range, intensity, ray_drop;

  RangeImage() = default;
  RangeImage(int h, int w)
      : height(h), width(w), range(size_t(h) * w, 0.f), intensity(size_t(h) * w, 0.f),
        ray_drop(size_t(h) * w, 0.f) {}
  size_t size() const { return size_t(height) * width; }
  size_t idx(int row, int col) const { return size_t(row) * width + col; }
};

struct PointXYZI {
  float x, y, z, intensity;
};

// Counts of points that the projection dropped on purpose (logged by callers, never silent).
struct ProjectionStats {
  size_t projected = 0, out_of_fov = 0, beyond_range = 0, below_min_range = 0, non_finite = 0,
         occluded = 0;
};

// Unit ray direction of pixel (row, col) in the sensor frame.
Eigen::Vector3f pixel_direction(const Sensor& s, int row, int col);
// All directions, row-major H×W×3.
std::vector<float> ray_directions(const Sensor& s);

// Points in the sensor frame → range image (nearest per pixel). Label = 1 where range > 0.
RangeImage project_points(const Sensor& s, const std::vector<PointXYZI>& pts,
                          ProjectionStats* stats = nullptr);
// Range image → points in the sensor frame (pixels with range 0 dropped).
std::vector<PointXYZI> unproject(const Sensor& s, const RangeImage& img);

}  // namespace sgnlf
