// ChannelCopy host launcher (kernels/conv/concat.cl).
#include "conv/channel_copy.hpp"

#include <string>

#include "conv/buffer_check.hpp"

namespace sgnlf::conv {

void ChannelCopyShape::validate() const {
  if (pixels < 1 || c < 1 || src_off < 0 || dst_off < 0 || src_cs < src_off + c ||
      dst_cs < dst_off + c)
    throw Error("ChannelCopy: bad shape pixels = " + std::to_string(pixels) + ", c = " +
                std::to_string(c) + ", src_cs = " + std::to_string(src_cs) + ", src_off = " +
                std::to_string(src_off) + ", dst_cs = " + std::to_string(dst_cs) +
                ", dst_off = " + std::to_string(dst_off) +
                " (needs offsets >= 0 and channel strides >= offset + c)");
}

ChannelCopy::ChannelCopy(cl::Runtime& rt) {
  k_ = rt.kernel("conv/concat.cl", "conv_copy_channels");
}

void ChannelCopy::run(const ChannelCopyShape& s, const cl::Buffer& src, cl::Buffer& dst,
                      bool accumulate) {
  s.validate();
  check_floats(src, size_t(s.pixels) * s.src_cs, "ChannelCopy", "src");
  check_floats(dst, size_t(s.pixels) * s.dst_cs, "ChannelCopy", "dst");
  k_.set_args(s.pixels, s.c, s.src_cs, s.src_off, s.dst_cs, s.dst_off, int(accumulate), src, dst);
  k_.launch({flat_global(size_t(s.pixels) * s.c, "ChannelCopy")}, {64});
}

}  // namespace sgnlf::conv
