// Input packing with box dropout (kernels/conv/box_mask.cl): LiDAR4D's ray-drop refinement
// zeroes random boxes of its (probability, intensity, depth) input while training (method.md
// §2). out = in · scale[c] outside every box, 0 inside; the same boxes for every image and
// channel. With n_boxes = 0 it is the inference-mode packing (per-channel scaling only).
#pragma once
#include "cl/runtime.hpp"

namespace sgnlf::conv {

struct BoxMaskShape {
  int n = 1, h = 1, w = 1;
  int c = 1;               // channels packed
  int in_cs = 1, out_cs = 1;
  void validate() const;   // throws Error naming the bad value
};

class BoxMask {
 public:
  explicit BoxMask(cl::Runtime& rt);
  // scale: >= c floats; boxes: int quadruples (y0, x0, y1, x1), half-open, of which n_boxes
  // from quadruple box_off are applied. Output channels c.. untouched. Enqueued, no wait.
  void run(const BoxMaskShape& s, const cl::Buffer& scale, const cl::Buffer& boxes, int box_off,
           int n_boxes, const cl::Buffer& in, cl::Buffer& out);

 private:
  cl::Kernel k_;
};

}  // namespace sgnlf::conv
