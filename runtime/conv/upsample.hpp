// Bilinear ×2 upsampling, align_corners = true (kernels/conv/upsample.cl): the up stages of
// LiDAR4D's ray-drop U-Net (method.md §2). The 2h × 2w result is written zero-padded into a
// target of th × tw (>= 2h × 2w; LiDAR4D pads it to the skip's size, e.g. 32 → 33) at offset
// ((th − 2h) / 2, (tw − 2w) / 2), and at channels [dst_off, dst_off + c) of the target, so it
// lands directly in the second half of the skip concatenation.
#pragma once
#include "cl/runtime.hpp"

namespace sgnlf::conv {

struct UpsampleShape {
  int n = 1, h = 1, w = 1;  // input images
  int c = 1;                // channels upsampled
  int in_cs = 1;            // channel stride of the input (>= c)
  int th = 2, tw = 2;       // target size (>= 2h, 2w)
  int out_cs = 1;           // channel stride of the target (>= dst_off + c)
  int dst_off = 0;          // first target channel written
  void validate() const;    // throws Error naming the bad value
};

class Upsample2x {
 public:
  explicit Upsample2x(cl::Runtime& rt);
  // Target channels [dst_off, dst_off + c) of every target pixel written (padding 0); other
  // channels untouched. Enqueued, no wait.
  void forward(const UpsampleShape& s, const cl::Buffer& in, cl::Buffer& out);
  // d_in (=|+=) upᵀ d_out (channels < c of d_in; d_out read at [dst_off, dst_off + c)). Enqueued.
  void backward(const UpsampleShape& s, const cl::Buffer& d_out, cl::Buffer& d_in,
                bool accumulate);

 private:
  cl::Kernel fwd_, bwd_;
};

}  // namespace sgnlf::conv
