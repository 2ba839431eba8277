// PNG pictures of range images: depth through the turbo colormap (perceptual, Google 2019),
// intensity in grey, the return mask in black/white; stacked vertically, rows repeated so that
// a 66-row scan is legible.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/range_image.hpp"

namespace sgnlf::io {

// 8-bit RGB image, row-major.
struct RgbImage {
  int height = 0, width = 0;
  std::vector<uint8_t> rgb;  // height × width × 3
};

void write_png(const std::string& path, const RgbImage& img);

// Turbo colormap at t ∈ [0, 1] (polynomial approximation by Mikhailov, 2019).
std::array<uint8_t, 3> turbo(double t);

struct RangePictureOptions {
  double max_range_m = 80.0;  // depth colour scale: turbo on log(1 + r) / log(1 + max)
  bool log_depth = true;      // false: turbo on r / max
  int row_repeat = 3;         // each scan row is drawn this many times
  int gap = 4;                // black rows between the panels
};

// A returning pixel's depth colour as range_image_picture draws it (turbo on the scale above).
std::array<uint8_t, 3> depth_colour(double range_m, const RangePictureOptions& opt);

// Depth (turbo, no return = black), intensity (grey), mask (white = return), stacked.
RgbImage range_image_picture(const RangeImage& img, const RangePictureOptions& opt = {});

}  // namespace sgnlf::io
