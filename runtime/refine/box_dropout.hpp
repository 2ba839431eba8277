// The boxes of LiDAR4D's box-dropout augmentation (Trainer.refine(), method.md §2), drawn on
// the host from the project's Philox generator (seed, stream "BX"), step after step: per step
// k ∈ [0, boxes_max) boxes, each of height in [1, hmax) and width in [1, wmax) (hmax =
// min(h, max(2, ⌊box_frac·h⌋)), likewise wmax), top-left corner uniform in [0, h − height) ×
// [0, w − width). LiDAR4D draws with NumPy's global generator instead; the distribution is the
// same, the draws are not.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

namespace sgnlf::refine {

struct BoxDraws {
  std::vector<int> boxes;   // (y0, x0, y1, x1) per box, half-open, all steps one after another
  std::vector<int> first;   // first box of each step
  std::vector<int> count;   // boxes of each step
};

// Boxes for `steps` steps on h × w images. boxes_max = 0 gives no boxes.
BoxDraws draw_boxes(uint64_t seed, int steps, int h, int w, int boxes_max, float box_frac);

}  // namespace sgnlf::refine
