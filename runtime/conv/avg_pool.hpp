// 2×2 average pooling with stride 2 on NHWC images with channel strides (kernels/conv/pool.cl):
// the multi-scale discriminator's input pyramid (method.md §4.3). Output h/2 × w/2 (floor; an
// odd last row or column is dropped and gets zero gradient).
#pragma once
#include "cl/runtime.hpp"

namespace sgnlf::conv {

struct PoolShape {
  int n = 1, h = 2, w = 2;
  int c = 1;       // channels pooled
  int in_cs = 1;   // channel stride of the input (>= c)
  int out_cs = 1;  // channel stride of the output (>= c)
  void validate() const;  // throws Error naming the bad value
  int out_h() const { return h / 2; }
  int out_w() const { return w / 2; }
};

class AvgPool2x2 {
 public:
  explicit AvgPool2x2(cl::Runtime& rt);
  // out = pool(in); channels c.. of the output are untouched. Enqueued, no wait.
  void forward(const PoolShape& s, const cl::Buffer& in, cl::Buffer& out);
  // d_in = pool'ᵀ d_out, or d_in += … with `accumulate` (channels < c only). Enqueued.
  void backward(const PoolShape& s, const cl::Buffer& d_out, cl::Buffer& d_in, bool accumulate);

 private:
  cl::Kernel fwd_, bwd_;
};

}  // namespace sgnlf::conv
