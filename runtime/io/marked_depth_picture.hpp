// Depth pictures with marked pixels, stacked: the error anatomy's picture (docs/anatomy.md),
// where a rendered range image shows its false returns and missed returns in colours that the
// turbo depth scale never takes.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "io/png_writer.hpp"

namespace sgnlf::io {

enum DepthMark : uint8_t { kMarkNone = 0, kMarkFalseReturn = 1, kMarkMissedReturn = 2 };
inline constexpr std::array<uint8_t, 3> kFalseReturnColour = {255, 0, 255};   // magenta
inline constexpr std::array<uint8_t, 3> kMissedReturnColour = {255, 255, 255};  // white

struct DepthPanel {
  const RangeImage* image = nullptr;   // depth drawn where range > 0, black elsewhere
  std::vector<uint8_t> marks;          // per pixel DepthMark; empty: none
};

// The panels' depth (turbo, as range_image_picture) with marked pixels in their colour, stacked
// top to bottom with opt.gap black rows between them. Error naming the panel whose image is
// missing, whose size differs from the first's, or whose marks do not match its pixels.
RgbImage marked_depth_picture(const std::vector<DepthPanel>& panels,
                              const RangePictureOptions& opt = {});

}  // namespace sgnlf::io
