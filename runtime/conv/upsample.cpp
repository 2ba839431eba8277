// Upsample2x host launcher (kernels/conv/upsample.cl).
#include "conv/upsample.hpp"

#include <string>

#include "conv/buffer_check.hpp"

namespace sgnlf::conv {

void UpsampleShape::validate() const {
  if (n < 1 || h < 1 || w < 1 || c < 1 || in_cs < c || th < 2 * h || tw < 2 * w ||
      dst_off < 0 || out_cs < dst_off + c)
    throw Error("Upsample2x: bad shape n = " + std::to_string(n) + ", h = " + std::to_string(h) +
                ", w = " + std::to_string(w) + ", c = " + std::to_string(c) + ", in_cs = " +
                std::to_string(in_cs) + ", target " + std::to_string(th) + " x " +
                std::to_string(tw) + ", out_cs = " + std::to_string(out_cs) + ", dst_off = " +
                std::to_string(dst_off) +
                " (needs in_cs >= c, a target of at least 2h x 2w, out_cs >= dst_off + c)");
}

Upsample2x::Upsample2x(cl::Runtime& rt) {
  fwd_ = rt.kernel("conv/upsample.cl", "conv_upsample2_fwd");
  bwd_ = rt.kernel("conv/upsample.cl", "conv_upsample2_bwd");
}

void Upsample2x::forward(const UpsampleShape& s, const cl::Buffer& in, cl::Buffer& out) {
  s.validate();
  check_floats(in, size_t(s.n) * s.h * s.w * s.in_cs, "Upsample2x", "in");
  const size_t pix = size_t(s.n) * s.th * s.tw;
  check_floats(out, pix * s.out_cs, "Upsample2x", "out");
  fwd_.set_args(s.n, s.h, s.w, s.c, s.in_cs, s.th, s.tw, s.out_cs, s.dst_off, in, out);
  fwd_.launch({flat_global(pix * s.c, "Upsample2x")}, {64});
}

void Upsample2x::backward(const UpsampleShape& s, const cl::Buffer& d_out, cl::Buffer& d_in,
                          bool accumulate) {
  s.validate();
  const size_t pix = size_t(s.n) * s.h * s.w;
  check_floats(d_out, size_t(s.n) * s.th * s.tw * s.out_cs, "Upsample2x", "d_out");
  check_floats(d_in, pix * s.in_cs, "Upsample2x", "d_in");
  bwd_.set_args(s.n, s.h, s.w, s.c, s.in_cs, s.th, s.tw, s.out_cs, s.dst_off, int(accumulate),
                d_out, d_in);
  bwd_.launch({flat_global(pix * s.c, "Upsample2x")}, {64});
}

}  // namespace sgnlf::conv
