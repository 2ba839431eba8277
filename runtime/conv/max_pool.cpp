// MaxPool2x2 host launcher (kernels/conv/maxpool.cl).
#include "conv/max_pool.hpp"

#include "conv/buffer_check.hpp"

namespace sgnlf::conv {

MaxPool2x2::MaxPool2x2(cl::Runtime& rt) {
  fwd_ = rt.kernel("conv/maxpool.cl", "conv_maxpool2_fwd");
  bwd_ = rt.kernel("conv/maxpool.cl", "conv_maxpool2_bwd");
}

void MaxPool2x2::forward(const PoolShape& s, const cl::Buffer& in, cl::Buffer& out) {
  s.validate();
  check_floats(in, size_t(s.n) * s.h * s.w * s.in_cs, "MaxPool2x2", "in");
  const size_t pix = size_t(s.n) * s.out_h() * s.out_w();
  check_floats(out, pix * s.out_cs, "MaxPool2x2", "out");
  fwd_.set_args(s.n, s.h, s.w, s.c, s.in_cs, s.out_cs, in, out);
  fwd_.launch({flat_global(pix * s.c, "MaxPool2x2")}, {64});
}

void MaxPool2x2::backward(const PoolShape& s, const cl::Buffer& in, const cl::Buffer& d_out,
                          cl::Buffer& d_in, bool accumulate) {
  s.validate();
  const size_t pix = size_t(s.n) * s.h * s.w;
  check_floats(in, pix * s.in_cs, "MaxPool2x2", "in");
  check_floats(d_out, size_t(s.n) * s.out_h() * s.out_w() * s.out_cs, "MaxPool2x2", "d_out");
  check_floats(d_in, pix * s.in_cs, "MaxPool2x2", "d_in");
  bwd_.set_args(s.n, s.h, s.w, s.c, s.in_cs, s.out_cs, int(accumulate), in, d_out, d_in);
  bwd_.launch({flat_global(pix * s.c, "MaxPool2x2")}, {64});
}

}  // namespace sgnlf::conv
