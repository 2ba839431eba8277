// draw_boxes (box_dropout.hpp).
#include "refine/box_dropout.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf::refine {

BoxDraws draw_boxes(uint64_t seed, int steps, int h, int w, int boxes_max, float box_frac) {
  if (steps < 0 || h < 2 || w < 2 || boxes_max < 0 || !(box_frac >= 0.0f && box_frac <= 1.0f))
    throw Error("draw_boxes: bad arguments steps = " + std::to_string(steps) + ", image " +
                std::to_string(h) + " x " + std::to_string(w) + ", boxes_max = " +
                std::to_string(boxes_max) + ", box_frac = " + std::to_string(box_frac));
  const int hmax = std::min(h, std::max(2, int(box_frac * float(h))));
  const int wmax = std::min(w, std::max(2, int(box_frac * float(w))));
  Rng rng(seed, 0x4258u);  // "BX"
  BoxDraws d;
  for (int s = 0; s < steps; ++s) {
    d.first.push_back(int(d.boxes.size() / 4));
    const int k = boxes_max > 0 ? int(rng.below(uint32_t(boxes_max))) : 0;
    for (int b = 0; b < k; ++b) {
      // One draw per statement: the order is fixed (core/rng.hpp).
      const int bh = 1 + int(rng.below(uint32_t(hmax - 1)));
      const int bw = 1 + int(rng.below(uint32_t(wmax - 1)));
      const int y0 = int(rng.below(uint32_t(h - bh)));
      const int x0 = int(rng.below(uint32_t(w - bw)));
      d.boxes.insert(d.boxes.end(), {y0, x0, y0 + bh, x0 + bw});
    }
    d.count.push_back(k);
  }
  return d;
}

}  // namespace sgnlf::refine
