// 2×2 max pooling with stride 2 on NHWC images with channel strides (kernels/conv/maxpool.cl):
// the down stages of LiDAR4D's ray-drop U-Net (method.md §2). Output h/2 × w/2 (floor; an odd
// last row or column is dropped and gets zero gradient). The gradient goes to the window's first
// maximum (row-major, strict >), recomputed from the forward input.
#pragma once
#include "cl/runtime.hpp"
#include "conv/avg_pool.hpp"  // PoolShape

namespace sgnlf::conv {

class MaxPool2x2 {
 public:
  explicit MaxPool2x2(cl::Runtime& rt);
  // out = maxpool(in); channels c.. of the output are untouched. Enqueued, no wait.
  void forward(const PoolShape& s, const cl::Buffer& in, cl::Buffer& out);
  // d_in = maxpool'ᵀ d_out (or d_in += … with `accumulate`), channels < c only; `in` is the
  // forward's input. Enqueued.
  void backward(const PoolShape& s, const cl::Buffer& in, const cl::Buffer& d_out,
                cl::Buffer& d_in, bool accumulate);

 private:
  cl::Kernel fwd_, bwd_;
};

}  // namespace sgnlf::conv
