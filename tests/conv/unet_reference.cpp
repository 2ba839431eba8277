// Host references of the U-Net layer kernels (unet_reference.hpp).
#include "unet_reference.hpp"

#include <algorithm>
#include <cmath>

namespace sgnlf::test::ref {
namespace {
size_t at(int n, int y, int x, int h, int w, int cs) {
  return ((size_t(n) * h + y) * w + x) * size_t(cs);
}

// PyTorch's align_corners = true taps of output index o (float arithmetic, as the kernel).
struct Taps {
  int i0, i1;
  float l0, l1;
};
Taps up_taps(int o, int in, int out) {
  const float scale = out > 1 ? float(in - 1) / float(out - 1) : 0.0f;
  const float s = scale * float(o);
  const int a = int(s);
  const float l1 = s - float(a);
  return {a, a + (a < in - 1 ? 1 : 0), 1.0f - l1, l1};
}
}  // namespace

std::vector<float> maxpool2_fwd(const conv::PoolShape& s, const std::vector<float>& in,
                                std::vector<float> out) {
  for (int n = 0; n < s.n; ++n)
    for (int oy = 0; oy < s.out_h(); ++oy)
      for (int ox = 0; ox < s.out_w(); ++ox)
        for (int c = 0; c < s.c; ++c) {
          float m = in[at(n, 2 * oy, 2 * ox, s.h, s.w, s.in_cs) + c];
          for (int k = 1; k < 4; ++k)
            m = std::max(m, in[at(n, 2 * oy + k / 2, 2 * ox + k % 2, s.h, s.w, s.in_cs) + c]);
          out[at(n, oy, ox, s.out_h(), s.out_w(), s.out_cs) + c] = m;
        }
  return out;
}

std::vector<float> maxpool2_bwd(const conv::PoolShape& s, const std::vector<float>& in,
                                const std::vector<float>& d_out, std::vector<float> d_in,
                                bool accumulate) {
  for (int n = 0; n < s.n; ++n)
    for (int y = 0; y < s.h; ++y)
      for (int x = 0; x < s.w; ++x)
        for (int c = 0; c < s.c; ++c)
          if (!accumulate) d_in[at(n, y, x, s.h, s.w, s.in_cs) + c] = 0.0f;
  for (int n = 0; n < s.n; ++n)
    for (int oy = 0; oy < s.out_h(); ++oy)
      for (int ox = 0; ox < s.out_w(); ++ox)
        for (int c = 0; c < s.c; ++c) {
          int best = 0;  // first maximum, row-major
          float m = in[at(n, 2 * oy, 2 * ox, s.h, s.w, s.in_cs) + c];
          for (int k = 1; k < 4; ++k) {
            const float v = in[at(n, 2 * oy + k / 2, 2 * ox + k % 2, s.h, s.w, s.in_cs) + c];
            if (v > m) {
              m = v;
              best = k;
            }
          }
          d_in[at(n, 2 * oy + best / 2, 2 * ox + best % 2, s.h, s.w, s.in_cs) + c] +=
              d_out[at(n, oy, ox, s.out_h(), s.out_w(), s.out_cs) + c];
        }
  return d_in;
}

std::vector<float> upsample2_fwd(const conv::UpsampleShape& s, const std::vector<float>& in,
                                 std::vector<float> out) {
  const int ho = 2 * s.h, wo = 2 * s.w, py = (s.th - ho) / 2, px = (s.tw - wo) / 2;
  for (int n = 0; n < s.n; ++n)
    for (int ty = 0; ty < s.th; ++ty)
      for (int tx = 0; tx < s.tw; ++tx)
        for (int c = 0; c < s.c; ++c) {
          const int oy = ty - py, ox = tx - px;
          double v = 0;
          if (oy >= 0 && oy < ho && ox >= 0 && ox < wo) {
            const Taps ty_ = up_taps(oy, s.h, ho), tx_ = up_taps(ox, s.w, wo);
            auto I = [&](int y, int x) { return double(in[at(n, y, x, s.h, s.w, s.in_cs) + c]); };
            v = ty_.l0 * (tx_.l0 * I(ty_.i0, tx_.i0) + tx_.l1 * I(ty_.i0, tx_.i1)) +
                ty_.l1 * (tx_.l0 * I(ty_.i1, tx_.i0) + tx_.l1 * I(ty_.i1, tx_.i1));
          }
          out[at(n, ty, tx, s.th, s.tw, s.out_cs) + s.dst_off + c] = float(v);
        }
  return out;
}

std::vector<float> upsample2_bwd(const conv::UpsampleShape& s, const std::vector<float>& d_out,
                                 std::vector<float> d_in, bool accumulate) {
  const int ho = 2 * s.h, wo = 2 * s.w, py = (s.th - ho) / 2, px = (s.tw - wo) / 2;
  std::vector<double> acc(size_t(s.n) * s.h * s.w * s.c, 0.0);
  for (int n = 0; n < s.n; ++n)
    for (int oy = 0; oy < ho; ++oy)
      for (int ox = 0; ox < wo; ++ox) {
        const Taps a = up_taps(oy, s.h, ho), b = up_taps(ox, s.w, wo);
        const int ys[2] = {a.i0, a.i1}, xs[2] = {b.i0, b.i1};
        const double wy[2] = {a.l0, a.l1}, wx[2] = {b.l0, b.l1};
        for (int c = 0; c < s.c; ++c) {
          const double g = d_out[at(n, oy + py, ox + px, s.th, s.tw, s.out_cs) + s.dst_off + c];
          for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j)
              acc[((size_t(n) * s.h + ys[i]) * s.w + xs[j]) * s.c + c] += wy[i] * wx[j] * g;
        }
      }
  for (size_t p = 0; p < size_t(s.n) * s.h * s.w; ++p)
    for (int c = 0; c < s.c; ++c) {
      float& d = d_in[p * s.in_cs + c];
      d = float((accumulate ? d : 0.0) + acc[p * s.c + c]);
    }
  return d_in;
}

std::vector<float> copy_channels(const conv::ChannelCopyShape& s, const std::vector<float>& src,
                                 std::vector<float> dst, bool accumulate) {
  for (size_t p = 0; p < size_t(s.pixels); ++p)
    for (int c = 0; c < s.c; ++c) {
      float& d = dst[p * s.dst_cs + s.dst_off + c];
      d = (accumulate ? d : 0.0f) + src[p * s.src_cs + s.src_off + c];
    }
  return dst;
}

double bce_with_logits(const std::vector<float>& logits, int count, int cs,
                       const std::vector<float>& target, std::vector<float>& d_logits) {
  d_logits.assign(size_t(count) * cs, 0.0f);
  double sum = 0;
  for (int i = 0; i < count; ++i) {
    const double z = logits[size_t(i) * cs], y = target[size_t(i)];
    const double p = 1.0 / (1.0 + std::exp(-z));
    sum += -(y * std::log(p) + (1.0 - y) * std::log1p(-p));  // the textbook form
    d_logits[size_t(i) * cs] = float((p - y) / count);
  }
  return sum / count;
}

std::vector<float> sigmoid(const std::vector<float>& logits, int count, int cs) {
  std::vector<float> p(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i)
    p[size_t(i)] = float(1.0 / (1.0 + std::exp(-double(logits[size_t(i) * cs]))));
  return p;
}

std::vector<float> box_mask(const conv::BoxMaskShape& s, const std::vector<float>& scale,
                            const std::vector<std::array<int, 4>>& boxes,
                            const std::vector<float>& in, std::vector<float> out) {
  for (int n = 0; n < s.n; ++n)
    for (int y = 0; y < s.h; ++y)
      for (int x = 0; x < s.w; ++x) {
        bool keep = true;
        for (const auto& b : boxes)
          keep = keep && !(y >= b[0] && x >= b[1] && y < b[2] && x < b[3]);
        for (int c = 0; c < s.c; ++c)
          out[at(n, y, x, s.h, s.w, s.out_cs) + c] =
              keep ? in[at(n, y, x, s.h, s.w, s.in_cs) + c] * scale[size_t(c)] : 0.0f;
      }
  return out;
}

}  // namespace sgnlf::test::ref
