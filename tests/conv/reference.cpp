// Host references of the conv kernels (reference.hpp).
#include "reference.hpp"

namespace sgnlf::test::ref {

std::vector<float> conv2d_fwd(const conv::Conv2dSpec& s, const std::vector<float>& params,
                              const std::vector<float>& in, int n, int h, int w) {
  const int ho = s.out_size(h), wo = s.out_size(w), ocs = s.out_cs(), ics = s.input_cs();
  std::vector<float> out(size_t(n) * ho * wo * ocs, 0.0f);
  for (int b = 0; b < n; ++b)
    for (int oy = 0; oy < ho; ++oy)
      for (int ox = 0; ox < wo; ++ox)
        for (int o = 0; o < s.c_out; ++o) {
          double acc = params[s.bias_index(o)];
          for (int ky = 0; ky < s.kernel; ++ky)
            for (int kx = 0; kx < s.kernel; ++kx) {
              const int iy = oy * s.stride - s.pad + ky, ix = ox * s.stride - s.pad + kx;
              if (iy < 0 || iy >= h || ix < 0 || ix >= w) continue;
              for (int c = 0; c < s.c_in; ++c)
                acc += double(in[((size_t(b) * h + iy) * w + ix) * ics + c]) *
                       params[s.weight_index(ky, kx, c, o)];
            }
          out[((size_t(b) * ho + oy) * wo + ox) * ocs + o] = float(acc);
        }
  return out;
}

std::vector<float> conv2d_bwd(const conv::Conv2dSpec& s, const std::vector<float>& params,
                              const std::vector<float>& in, int n, int h, int w,
                              const std::vector<float>& d_out, std::vector<float>& d_in) {
  const int ho = s.out_size(h), wo = s.out_size(w), ocs = s.out_cs(), ics = s.input_cs();
  std::vector<double> g(s.n_params(), 0.0), di(size_t(n) * h * w * ics, 0.0);
  for (int b = 0; b < n; ++b)
    for (int oy = 0; oy < ho; ++oy)
      for (int ox = 0; ox < wo; ++ox)
        for (int o = 0; o < s.c_out; ++o) {
          const double d = d_out[((size_t(b) * ho + oy) * wo + ox) * ocs + o];
          g[s.bias_index(o)] += d;
          for (int ky = 0; ky < s.kernel; ++ky)
            for (int kx = 0; kx < s.kernel; ++kx) {
              const int iy = oy * s.stride - s.pad + ky, ix = ox * s.stride - s.pad + kx;
              if (iy < 0 || iy >= h || ix < 0 || ix >= w) continue;
              for (int c = 0; c < s.c_in; ++c) {
                const size_t ii = ((size_t(b) * h + iy) * w + ix) * ics + c;
                g[s.weight_index(ky, kx, c, o)] += d * in[ii];
                di[ii] += d * params[s.weight_index(ky, kx, c, o)];
              }
            }
        }
  d_in.assign(di.begin(), di.end());
  return std::vector<float>(g.begin(), g.end());
}

std::vector<float> leaky_relu_fwd(const std::vector<float>& x, float slope) {
  std::vector<float> y(x.size());
  for (size_t i = 0; i < x.size(); ++i) y[i] = x[i] > 0.0f ? x[i] : slope * x[i];
  return y;
}

std::vector<float> leaky_relu_bwd(const std::vector<float>& x, const std::vector<float>& dy,
                                  float slope) {
  std::vector<float> dx(x.size());
  for (size_t i = 0; i < x.size(); ++i) dx[i] = x[i] > 0.0f ? dy[i] : slope * dy[i];
  return dx;
}

std::vector<float> avgpool2_fwd(const conv::PoolShape& s, const std::vector<float>& in,
                                std::vector<float> out) {
  const int ho = s.out_h(), wo = s.out_w();
  for (int b = 0; b < s.n; ++b)
    for (int y = 0; y < ho; ++y)
      for (int x = 0; x < wo; ++x)
        for (int c = 0; c < s.c; ++c) {
          double acc = 0;
          for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx)
              acc += in[((size_t(b) * s.h + 2 * y + dy) * s.w + 2 * x + dx) * s.in_cs + c];
          out[((size_t(b) * ho + y) * wo + x) * s.out_cs + c] = float(0.25 * acc);
        }
  return out;
}

std::vector<float> avgpool2_bwd(const conv::PoolShape& s, const std::vector<float>& d_out,
                                std::vector<float> d_in, bool accumulate) {
  const int ho = s.out_h(), wo = s.out_w();
  for (int b = 0; b < s.n; ++b)
    for (int y = 0; y < s.h; ++y)
      for (int x = 0; x < s.w; ++x)
        for (int c = 0; c < s.c; ++c) {
          const float g = (y / 2 < ho && x / 2 < wo)
                              ? 0.25f * d_out[((size_t(b) * ho + y / 2) * wo + x / 2) * s.out_cs + c]
                              : 0.0f;
          float& dst = d_in[((size_t(b) * s.h + y) * s.w + x) * s.in_cs + c];
          dst = accumulate ? dst + g : g;
        }
  return d_in;
}

}  // namespace sgnlf::test::ref
