// Host reference implementations of the conv kernels, for tests only (the runtime never calls
// them). Plain loops in the order the formulas read, double accumulation; layouts as in
// runtime/conv/conv2d.hpp (NHWC with channel strides, parameter slice W[tap·c_in + c][out_cs]
// then bias).
#pragma once
#include <vector>

#include "conv/avg_pool.hpp"
#include "conv/conv2d.hpp"

namespace sgnlf::test::ref {

// out (n × ho × wo × out_cs, padding channels 0).
std::vector<float> conv2d_fwd(const conv::Conv2dSpec& s, const std::vector<float>& params,
                              const std::vector<float>& in, int n, int h, int w);
// Returns dL/dparams (slice layout, padding 0); fills d_in (input layout, padding channels 0).
std::vector<float> conv2d_bwd(const conv::Conv2dSpec& s, const std::vector<float>& params,
                              const std::vector<float>& in, int n, int h, int w,
                              const std::vector<float>& d_out, std::vector<float>& d_in);

std::vector<float> leaky_relu_fwd(const std::vector<float>& x, float slope);
std::vector<float> leaky_relu_bwd(const std::vector<float>& x, const std::vector<float>& dy,
                                  float slope);

// Output channels c.. keep the values of `out_init` (the kernel leaves them untouched).
std::vector<float> avgpool2_fwd(const conv::PoolShape& s, const std::vector<float>& in,
                                std::vector<float> out_init);
std::vector<float> avgpool2_bwd(const conv::PoolShape& s, const std::vector<float>& d_out,
                                std::vector<float> d_in_init, bool accumulate);

}  // namespace sgnlf::test::ref
