// pixel_boundaries() (see pixel_boundaries.hpp).
#include "geometry/pixel_boundaries.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace sgnlf {

PixelBoundaries pixel_boundaries(const Sensor& s) {
  s.validate();
  if (s.width < kMinBoundaryWidth)
    throw ConfigError("sensor '" + s.name + "': width " + std::to_string(s.width) +
                      " is below " + std::to_string(kMinBoundaryWidth) +
                      ", too few columns to project points by pixel-boundary tests");
  PixelBoundaries b;
  b.col.resize(2 * size_t(s.width));
  for (int k = 0; k < s.width; ++k) {
    const double beta = M_PI - (k + 0.5) * 2.0 * M_PI / s.width;
    b.col[2 * size_t(k)] = std::cos(beta);
    b.col[2 * size_t(k) + 1] = std::sin(beta);
  }
  b.row.resize(2 * size_t(s.height + 1));
  for (int k = -1; k < s.height; ++k) {
    const double e = (s.fov_up_deg - (k + 0.5) * s.fov_deg / s.height) * M_PI / 180.0;
    b.row[2 * size_t(k + 1)] = std::cos(e);
    b.row[2 * size_t(k + 1) + 1] = std::sin(e);
  }
  return b;
}

}  // namespace sgnlf
