// The pixel boundaries of a range image (protocol §1) as unit vectors, so that a point can be
// put into its pixel by sign tests instead of rounding atan2: with a fixed sequence of IEEE
// multiplications, additions and comparisons the decision is the same bit for bit on the host
// and on every OpenCL device (the cross-frame reprojection, render/cross_frame_reprojection.hpp).
//
// The protocol's column c = round((π − β)/(2π/W)) of a point at azimuth β = atan2(y, x) changes
// at b_k = π − (k + ½)·2π/W, and its row r = round(H − (α + fov_down)/(fov/H)) of elevation α at
// e_k = fov_up − (k + ½)·fov/H (degrees); round() sends halves up, so a point exactly on a
// boundary belongs to the higher index. Hence, for a point (x, y, z):
//   column c ⇔ (c = 0 or β ≤ b_{c−1}) and β > b_c, c = W being outside (the protocol drops it);
//   row r    ⇔ (r = 0 or α ≤ e_{r−1}) and α > e_r, rows −1 and H being outside.
// β > b ⇔ cos b·y − sin b·x > 0 and α > e ⇔ cos e·z − sin e·√(x² + y²) > 0, valid while the
// angle between point and boundary is below π: always for rows, and for columns within half
// a turn of the boundary (two columns are a quarter turn at most for W ≥ 8).
#pragma once
#include <vector>

#include "geometry/sensor.hpp"

namespace sgnlf {

// Smallest width for which the sign tests above are unambiguous two columns away.
constexpr int kMinBoundaryWidth = 8;

struct PixelBoundaries {
  std::vector<double> col;  // W × 2: (cos b_k, sin b_k), k = 0 … W−1
  std::vector<double> row;  // (H + 1) × 2: (cos e_k, sin e_k), k = −1 … H−1 stored at k + 1
};

// Throws ConfigError when the sensor is invalid or narrower than kMinBoundaryWidth.
PixelBoundaries pixel_boundaries(const Sensor& s);

}  // namespace sgnlf
