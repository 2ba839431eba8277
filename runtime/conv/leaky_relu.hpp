// Leaky ReLU on a flat device buffer (kernels/conv/activation.cl): y = x (x > 0), slope · x
// otherwise; backward from the forward input x. Used between the discriminator's convolutions
// (method.md §4.3: slope 0.2). Padding channels (zero) stay zero in both directions.
#pragma once
#include "cl/runtime.hpp"

namespace sgnlf::conv {

class LeakyRelu {
 public:
  // slope in [0, 1]; throws ConfigError otherwise.
  LeakyRelu(cl::Runtime& rt, float slope);
  float slope() const { return slope_; }
  // y[0, count) = f(x[0, count)). Enqueued, no wait; x and y may be the same buffer.
  void forward(const cl::Buffer& x, size_t count, cl::Buffer& y);
  // dx[0, count) = f'(x) · dy. Enqueued, no wait; dy and dx may be the same buffer.
  void backward(const cl::Buffer& x, const cl::Buffer& dy, size_t count, cl::Buffer& dx);

 private:
  float slope_;
  cl::Kernel fwd_, bwd_;
};

}  // namespace sgnlf::conv
