// BoxMask host launcher (kernels/conv/box_mask.cl).
#include "conv/box_mask.hpp"

#include <string>

#include "conv/buffer_check.hpp"

namespace sgnlf::conv {

void BoxMaskShape::validate() const {
  if (n < 1 || h < 1 || w < 1 || c < 1 || in_cs < c || out_cs < c)
    throw Error("BoxMask: bad shape n = " + std::to_string(n) + ", h = " + std::to_string(h) +
                ", w = " + std::to_string(w) + ", c = " + std::to_string(c) + ", in_cs = " +
                std::to_string(in_cs) + ", out_cs = " + std::to_string(out_cs) +
                " (needs sizes >= 1 and channel strides >= c)");
}

BoxMask::BoxMask(cl::Runtime& rt) { k_ = rt.kernel("conv/box_mask.cl", "conv_box_mask"); }

void BoxMask::run(const BoxMaskShape& s, const cl::Buffer& scale, const cl::Buffer& boxes,
                  int box_off, int n_boxes, const cl::Buffer& in, cl::Buffer& out) {
  s.validate();
  if (box_off < 0 || n_boxes < 0 ||
      size_t(box_off + n_boxes) * 4 * sizeof(int) > boxes.bytes())
    throw Error("BoxMask: boxes [" + std::to_string(box_off) + ", +" + std::to_string(n_boxes) +
                ") exceed a buffer of " + std::to_string(boxes.bytes() / (4 * sizeof(int))) +
                " boxes");
  check_floats(scale, size_t(s.c), "BoxMask", "scale");
  const size_t pix = size_t(s.n) * s.h * s.w;
  check_floats(in, pix * s.in_cs, "BoxMask", "in");
  check_floats(out, pix * s.out_cs, "BoxMask", "out");
  k_.set_args(s.n, s.h, s.w, s.c, s.in_cs, s.out_cs, scale, n_boxes, box_off, boxes, in, out);
  k_.launch({flat_global(pix * s.c, "BoxMask")}, {64});
}

}  // namespace sgnlf::conv
