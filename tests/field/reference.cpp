// Host references of the field kernels (tests only).
#include "reference.hpp"

#include <algorithm>
#include <cmath>

namespace sgnlf::test::ref {
namespace {

struct Corners {
  uint32_t idx[8];
  float w[8];      // trilinear weights
  float dw[8][3];  // ∂w/∂pos_d
};

uint32_t grid_index(uint32_t gx, uint32_t gy, uint32_t gz, const field::HashGridLevel& lv) {
  if (lv.hashed) return (gx ^ (gy * 2654435761u) ^ (gz * 805459861u)) & (lv.size - 1u);
  const uint32_t r1 = lv.res - 1;
  return std::min(gx, r1) + (std::min(gy, r1) + std::min(gz, r1) * lv.res) * lv.res;
}

Corners corners(const float* x, const field::HashGridLevel& lv) {
  uint32_t g[3];
  float fr[3];
  for (int d = 0; d < 3; ++d) {
    const float x01 = std::fma(x[d], 0.5f, 0.5f);
    const float pos = std::fma(x01, lv.scale, 0.5f);
    const float fl = std::floor(pos);
    g[d] = uint32_t(int32_t(fl));
    fr[d] = pos - fl;
  }
  Corners c{};
  for (int k = 0; k < 8; ++k) {
    const int b[3] = {k & 1, (k >> 1) & 1, k >> 2};
    float w1[3], s[3];
    for (int d = 0; d < 3; ++d) {
      w1[d] = b[d] ? fr[d] : 1.0f - fr[d];
      s[d] = b[d] ? 1.0f : -1.0f;
    }
    c.idx[k] = grid_index(g[0] + b[0], g[1] + b[1], g[2] + b[2], lv);
    c.w[k] = w1[0] * w1[1] * w1[2];
    c.dw[k][0] = s[0] * w1[1] * w1[2];
    c.dw[k][1] = w1[0] * s[1] * w1[2];
    c.dw[k][2] = w1[0] * w1[1] * s[2];
  }
  return c;
}

double act(double z, field::Activation a) {
  switch (a) {
    case field::Activation::Relu: return z > 0 ? z : 0;
    case field::Activation::Tanh: return std::tanh(z);
    case field::Activation::Softplus: return std::log1p(std::exp(-std::fabs(z))) + std::fmax(z, 0);
    case field::Activation::Sine: return std::sin(z);
    default: return z;
  }
}
double act_grad(double z, field::Activation a) {
  switch (a) {
    case field::Activation::Relu: return z > 0 ? 1 : 0;
    case field::Activation::Tanh: return 1 - std::tanh(z) * std::tanh(z);
    case field::Activation::Softplus: return 1 / (1 + std::exp(-z));
    case field::Activation::Sine: return std::cos(z);
    default: return 1;
  }
}

}  // namespace

std::vector<float> hashgrid_fwd(const field::HashGridConfig& cfg, const std::vector<float>& table,
                                const std::vector<float>& x, const std::vector<float>& weights) {
  const auto levels = field::hash_grid_levels(cfg);
  const int F = cfg.features, L = cfg.levels;
  const size_t n = x.size() / 3;
  std::vector<float> enc(n * L * F, 0.0f);
  for (size_t i = 0; i < n; ++i)
    for (int l = 0; l < L; ++l) {
      if (weights[l] == 0.0f) continue;
      const auto c = corners(&x[3 * i], levels[l]);
      for (int f = 0; f < F; ++f) {
        double s = 0;
        for (int k = 0; k < 8; ++k)
          s += double(c.w[k]) * table[(size_t(levels[l].offset) + c.idx[k]) * F + f];
        enc[(i * L + l) * F + f] = float(weights[l] * s);
      }
    }
  return enc;
}

std::vector<float> hashgrid_bwd(const field::HashGridConfig& cfg, size_t n_params,
                                const std::vector<float>& x, const std::vector<float>& weights,
                                const std::vector<float>& d_enc) {
  const auto levels = field::hash_grid_levels(cfg);
  const int F = cfg.features, L = cfg.levels;
  const size_t n = x.size() / 3;
  std::vector<double> g(n_params, 0.0);
  for (size_t i = 0; i < n; ++i)
    for (int l = 0; l < L; ++l) {
      if (weights[l] == 0.0f) continue;
      const auto c = corners(&x[3 * i], levels[l]);
      for (int k = 0; k < 8; ++k)
        for (int f = 0; f < F; ++f)
          g[(size_t(levels[l].offset) + c.idx[k]) * F + f] +=
              double(c.w[k]) * weights[l] * d_enc[(i * L + l) * F + f];
    }
  return std::vector<float>(g.begin(), g.end());
}

std::vector<float> hashgrid_bwd_dx(const field::HashGridConfig& cfg,
                                   const std::vector<float>& table, const std::vector<float>& x,
                                   const std::vector<float>& weights,
                                   const std::vector<float>& d_enc) {
  const auto levels = field::hash_grid_levels(cfg);
  const int F = cfg.features, L = cfg.levels;
  const size_t n = x.size() / 3;
  std::vector<float> dx(n * 3, 0.0f);
  for (size_t i = 0; i < n; ++i) {
    double acc[3] = {0, 0, 0};
    for (int l = 0; l < L; ++l) {
      if (weights[l] == 0.0f) continue;
      const auto c = corners(&x[3 * i], levels[l]);
      for (int k = 0; k < 8; ++k) {
        double v = 0;
        for (int f = 0; f < F; ++f)
          v += double(d_enc[(i * L + l) * F + f]) * table[(size_t(levels[l].offset) + c.idx[k]) * F + f];
        for (int d = 0; d < 3; ++d)
          acc[d] += double(weights[l]) * levels[l].scale * 0.5 * c.dw[k][d] * v;
      }
    }
    for (int d = 0; d < 3; ++d) dx[3 * i + d] = float(acc[d]);
  }
  return dx;
}

namespace {
// Forward keeping pre-activations z[l] and outputs a[l] (a[-1] = input), in double.
void mlp_forward_all(const field::MlpSpec& spec, const std::vector<float>& params,
                     const std::vector<float>& in, int n, std::vector<std::vector<double>>& z,
                     std::vector<std::vector<double>>& a) {
  a.assign(1, std::vector<double>(in.begin(), in.end()));
  z.clear();
  int n_in = spec.n_in;
  size_t off = 0;
  for (const auto& ls : spec.layers) {
    const int op = field::Mlp::pad16(ls.width);
    std::vector<double> zl(size_t(n) * ls.width), al(zl.size());
    for (int p = 0; p < n; ++p)
      for (int o = 0; o < ls.width; ++o) {
        double s = params[off + size_t(n_in) * op + o];
        for (int i = 0; i < n_in; ++i)
          s += a.back()[size_t(p) * n_in + i] * params[off + size_t(i) * op + o];
        zl[size_t(p) * ls.width + o] = s;
        al[size_t(p) * ls.width + o] = act(s, ls.activation);
      }
    z.push_back(zl);
    a.push_back(al);
    off += size_t(n_in + 1) * op;
    n_in = ls.width;
  }
}
}  // namespace

std::vector<float> mlp_fwd(const field::MlpSpec& spec, const std::vector<float>& params,
                           const std::vector<float>& in, int n) {
  std::vector<std::vector<double>> z, a;
  mlp_forward_all(spec, params, in, n, z, a);
  return std::vector<float>(a.back().begin(), a.back().end());
}

std::vector<float> mlp_bwd(const field::MlpSpec& spec, const std::vector<float>& params,
                           const std::vector<float>& in, int n, const std::vector<float>& d_out,
                           std::vector<float>& d_in) {
  std::vector<std::vector<double>> z, a;
  mlp_forward_all(spec, params, in, n, z, a);
  std::vector<size_t> offs;
  size_t total = 0;
  int n_in = spec.n_in;
  for (const auto& ls : spec.layers) {
    offs.push_back(total);
    total += size_t(n_in + 1) * field::Mlp::pad16(ls.width);
    n_in = ls.width;
  }
  std::vector<double> grad(total, 0.0);
  std::vector<double> d(d_out.begin(), d_out.end());  // dL/d(output of layer l)
  for (int l = int(spec.layers.size()) - 1; l >= 0; --l) {
    const auto& ls = spec.layers[size_t(l)];
    const int width = ls.width, op = field::Mlp::pad16(width);
    const int ni = l == 0 ? spec.n_in : spec.layers[size_t(l - 1)].width;
    std::vector<double> dz(d.size());
    for (size_t k = 0; k < d.size(); ++k) dz[k] = d[k] * act_grad(z[size_t(l)][k], ls.activation);
    std::vector<double> dprev(size_t(n) * ni, 0.0);
    for (int p = 0; p < n; ++p)
      for (int o = 0; o < width; ++o) {
        const double g = dz[size_t(p) * width + o];
        grad[offs[size_t(l)] + size_t(ni) * op + o] += g;
        for (int i = 0; i < ni; ++i) {
          grad[offs[size_t(l)] + size_t(i) * op + o] += g * a[size_t(l)][size_t(p) * ni + i];
          dprev[size_t(p) * ni + i] += g * params[offs[size_t(l)] + size_t(i) * op + o];
        }
      }
    d = dprev;
  }
  d_in.assign(d.begin(), d.end());
  return std::vector<float>(grad.begin(), grad.end());
}

std::vector<float> direnc_fwd(const std::vector<float>& dir, int n_freq) {
  const size_t r = dir.size() / 3;
  std::vector<float> enc(r * 6 * n_freq);
  for (size_t i = 0; i < r; ++i)
    for (int k = 0; k < n_freq; ++k)
      for (int j = 0; j < 3; ++j) {
        const double a = std::ldexp(double(dir[3 * i + j]), k);
        enc[i * 6 * n_freq + k * 6 + j] = float(std::sin(a));
        enc[i * 6 * n_freq + k * 6 + 3 + j] = float(std::cos(a));
      }
  return enc;
}

std::vector<float> direnc_bwd(const std::vector<float>& dir, int n_freq,
                              const std::vector<float>& d_enc) {
  const size_t r = dir.size() / 3;
  std::vector<float> d_dir(r * 3);
  for (size_t i = 0; i < r; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0;
      for (int k = 0; k < n_freq; ++k) {
        const double f = std::ldexp(1.0, k), a = f * dir[3 * i + j];
        s += f * (d_enc[i * 6 * n_freq + k * 6 + j] * std::cos(a) -
                  d_enc[i * 6 * n_freq + k * 6 + 3 + j] * std::sin(a));
      }
      d_dir[3 * i + j] = float(s);
    }
  return d_dir;
}

std::vector<float> head_input_fwd(const std::vector<float>& dens, const std::vector<float>& enc,
                                  int n_rays, int samples, int n_geo, int geo_start,
                                  int dens_stride, int enc_dim) {
  const size_t n = size_t(n_rays) * samples, w = size_t(n_geo + enc_dim);
  std::vector<float> out(n * w);
  for (size_t i = 0; i < n; ++i) {
    for (int j = 0; j < n_geo; ++j) out[i * w + j] = dens[i * dens_stride + geo_start + j];
    for (int j = 0; j < enc_dim; ++j) out[i * w + n_geo + j] = enc[(i / samples) * enc_dim + j];
  }
  return out;
}

void adam_step(std::vector<float>& p, const std::vector<float>& g, std::vector<float>& m,
               std::vector<float>& v, size_t offset, size_t count, float lr, int64_t t,
               float beta1, float beta2, float eps, float weight_decay) {
  const double c1 = 1.0 / (1.0 - std::pow(double(beta1), double(t)));
  const double c2 = 1.0 / std::sqrt(1.0 - std::pow(double(beta2), double(t)));
  for (size_t k = offset; k < offset + count; ++k) {
    const double gk = g[k] + double(weight_decay) * p[k];
    m[k] = float(beta1 * double(m[k]) + (1.0 - beta1) * gk);
    v[k] = float(beta2 * double(v[k]) + (1.0 - beta2) * gk * gk);
    p[k] = float(p[k] - lr * (m[k] * c1) / (std::sqrt(double(v[k])) * c2 + eps));
  }
}

}  // namespace sgnlf::test::ref
