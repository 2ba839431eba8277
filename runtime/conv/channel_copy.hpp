// Channel copy between NHWC images with channel strides and offsets (kernels/conv/concat.cl):
// the skip half of the U-Net's concatenation [skip, upsampled] (method.md §2) and, backward,
// its split back onto the skip's gradient (accumulating where the skip also feeds a down stage).
// The upsampled half is written in place by Upsample2x (dst_off).
#pragma once
#include "cl/runtime.hpp"

namespace sgnlf::conv {

struct ChannelCopyShape {
  int pixels = 1;   // n · h · w
  int c = 1;        // channels copied
  int src_cs = 1, src_off = 0;
  int dst_cs = 1, dst_off = 0;
  void validate() const;  // throws Error naming the bad value
};

class ChannelCopy {
 public:
  explicit ChannelCopy(cl::Runtime& rt);
  // dst[p, dst_off + k] (=|+=) src[p, src_off + k], k < c. Enqueued, no wait.
  void run(const ChannelCopyShape& s, const cl::Buffer& src, cl::Buffer& dst, bool accumulate);

 private:
  cl::Kernel k_;
};

}  // namespace sgnlf::conv
