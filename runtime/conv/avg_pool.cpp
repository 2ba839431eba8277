// AvgPool2x2 host launcher (kernels/conv/pool.cl).
#include "conv/avg_pool.hpp"

#include <string>

#include "core/error.hpp"

namespace sgnlf::conv {
namespace {
void check(const cl::Buffer& b, size_t floats, const char* what) {
  if (b.bytes() < floats * sizeof(float))
    throw Error(std::string("AvgPool2x2: buffer '") + what + "' has " +
                std::to_string(b.bytes()) + " bytes, needs " + std::to_string(floats * sizeof(float)));
}
}  // namespace

void PoolShape::validate() const {
  if (n < 1 || h < 2 || w < 2 || c < 1 || in_cs < c || out_cs < c)
    throw Error("AvgPool2x2: bad shape n = " + std::to_string(n) + ", h = " + std::to_string(h) +
                ", w = " + std::to_string(w) + ", c = " + std::to_string(c) + ", in_cs = " +
                std::to_string(in_cs) + ", out_cs = " + std::to_string(out_cs) +
                " (needs h, w >= 2 and channel strides >= c)");
}

AvgPool2x2::AvgPool2x2(cl::Runtime& rt) {
  fwd_ = rt.kernel("conv/pool.cl", "conv_avgpool2_fwd");
  bwd_ = rt.kernel("conv/pool.cl", "conv_avgpool2_bwd");
}

void AvgPool2x2::forward(const PoolShape& s, const cl::Buffer& in, cl::Buffer& out) {
  s.validate();
  check(in, size_t(s.n) * s.h * s.w * s.in_cs, "in");
  const size_t pix = size_t(s.n) * s.out_h() * s.out_w();
  check(out, pix * s.out_cs, "out");
  fwd_.set_args(s.n, s.h, s.w, s.c, s.in_cs, s.out_cs, in, out);
  fwd_.launch({cl::round_up(pix, 64), size_t(s.c)}, {64, 1});
}

void AvgPool2x2::backward(const PoolShape& s, const cl::Buffer& d_out, cl::Buffer& d_in,
                          bool accumulate) {
  s.validate();
  const size_t pix = size_t(s.n) * s.h * s.w;
  check(d_out, size_t(s.n) * s.out_h() * s.out_w() * s.out_cs, "d_out");
  check(d_in, pix * s.in_cs, "d_in");
  bwd_.set_args(s.n, s.h, s.w, s.c, s.in_cs, s.out_cs, int(accumulate), d_out, d_in);
  bwd_.launch({cl::round_up(pix, 64), size_t(s.c)}, {64, 1});
}

}  // namespace sgnlf::conv
