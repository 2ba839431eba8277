// Host reference implementations of every kernel in kernels/render/ (tests only; the runtime
// never calls them). Templated on the scalar so that float versions check the device and
// double versions serve the finite-difference gradient tests.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/rng.hpp"

namespace sgnlf::test {

template <typename T>
using Vec = std::vector<T>;

inline constexpr uint32_t kStreamUniform = 0x52454e31u, kStreamImportance = 0x52454e32u;

inline float ref_jitter(uint64_t seed, uint32_t stream, uint32_t step, uint32_t counter) {
  return u32_to_unit_float(philox_block(seed, stream, (uint64_t(step) << 32) | counter)[0]);
}

// render_sample_uniform
inline void ref_sample_uniform(int n_rays, int S, float near, float far, bool jitter, uint64_t seed,
                               uint32_t step, const Vec<float>& o, const Vec<float>& d,
                               Vec<float>& t, Vec<float>& x) {
  t.assign(size_t(n_rays) * S, 0.f);
  x.assign(t.size() * 3, 0.f);
  for (int s = 0; s < n_rays * S; ++s) {
    const int r = s / S, i = s % S;
    const uint32_t quad = uint32_t(r * ((S + 3) / 4) + i / 4);
    const float xi = jitter ? u32_to_unit_float(philox_block(seed, kStreamUniform,
                                                             (uint64_t(step) << 32) | quad)[i % 4])
                            : 0.5f;
    t[s] = near + (float(i) + xi) * ((far - near) / float(S));
    for (int c = 0; c < 3; ++c) x[3 * s + c] = o[3 * r + c] + t[s] * d[3 * r + c];
  }
}

// render_sample_importance: inverse CDF over bins between coarse midpoints, merged sorted.
inline void ref_sample_importance(int n_rays, int Sc, int Sf, float near, float far, bool jitter,
                                  uint64_t seed, uint32_t step, const Vec<float>& o,
                                  const Vec<float>& d, const Vec<float>& tc, const Vec<float>& wc,
                                  Vec<float>& t, Vec<float>& x, Vec<int>* src = nullptr) {
  const int So = Sc + Sf;
  t.assign(size_t(n_rays) * So, 0.f);
  if (src) src->assign(t.size(), -1);
  x.assign(t.size() * 3, 0.f);
  for (int r = 0; r < n_rays; ++r) {
    const float* tr = &tc[size_t(r) * Sc];
    const float* wr = &wc[size_t(r) * Sc];
    std::vector<float> edges(Sc + 1), p(Sc), fine(Sf);
    edges[0] = near;
    edges[Sc] = far;
    for (int k = 1; k < Sc; ++k) edges[k] = 0.5f * (tr[k - 1] + tr[k]);
    float total = 0.f;
    for (int k = 0; k < Sc; ++k) total += wr[k] + 1e-5f;
    for (int k = 0; k < Sc; ++k) p[k] = (wr[k] + 1e-5f) * (1.0f / total);
    for (int j = 0; j < Sf; ++j) {
      const float xi =
          jitter ? ref_jitter(seed, kStreamImportance, step, uint32_t(r * Sf + j)) : 0.5f;
      const float u = (float(j) + xi) / float(Sf);
      int k = 0;
      float cdf = 0.f;
      while (k < Sc - 1 && cdf + p[k] <= u) cdf += p[k++];
      const float f = std::clamp((u - cdf) / p[k], 0.f, 1.f);
      fine[j] = edges[k] + f * (edges[k + 1] - edges[k]);
    }
    std::vector<std::pair<float, int>> merged;  // (t, source: k coarse, Sc + j fine)
    for (int k = 0; k < Sc; ++k) merged.emplace_back(tr[k], k);
    for (int j = 0; j < Sf; ++j) merged.emplace_back(fine[j], Sc + j);
    // Coarse first on ties, as the kernel.
    std::stable_sort(merged.begin(), merged.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (int i = 0; i < So; ++i) {
      const size_t s = size_t(r) * So + i;
      t[s] = merged[i].first;
      if (src) (*src)[s] = merged[i].second;
      for (int c = 0; c < 3; ++c) x[3 * s + c] = o[3 * r + c] + t[s] * d[3 * r + c];
    }
  }
}

template <typename T>
T ref_sigmoid(T v) {
  return T(1) / (T(1) + std::exp(-v));
}

// render_volume_fwd: out (n x 3) and weights (N).
template <typename T>
void ref_volume_fwd(int n_rays, int S, T last_delta, const Vec<T>& t, const Vec<T>& h0,
                    const Vec<T>& head, Vec<T>& out, Vec<T>& w) {
  out.assign(size_t(n_rays) * 3, T(0));
  w.assign(size_t(n_rays) * S, T(0));
  for (int r = 0; r < n_rays; ++r) {
    T trans = 1;
    for (int i = 0; i < S; ++i) {
      const size_t s = size_t(r) * S + i;
      const T delta = i + 1 < S ? t[s + 1] - t[s] : last_delta;
      const T e = std::exp(-std::exp(std::min(h0[s], T(80))) * delta);
      w[s] = trans * (T(1) - e);
      out[3 * r] += w[s] * t[s];
      out[3 * r + 1] += w[s] * ref_sigmoid(head[2 * s]);
      out[3 * r + 2] += w[s] * ref_sigmoid(head[2 * s + 1]);
      trans *= e;
    }
  }
}

// render_median_depth, in double from the forward's weights: per ray the index of the first
// sample where the running weight sum reaches 1/2 (else the last sample), the running sum just
// before it, and the range where the transmittance falls to 1/2 inside that sample's interval.
struct RefMedian {
  std::vector<int> index;
  std::vector<double> before, depth;
  std::vector<char> crossed;  // the running sum reached 1/2
};
inline RefMedian ref_median_depth(int n_rays, int S, double last_delta, const Vec<float>& t,
                                  const Vec<float>& w) {
  RefMedian m;
  m.index.assign(size_t(n_rays), S - 1);
  m.before.assign(size_t(n_rays), 0.0);
  m.depth.assign(size_t(n_rays), 0.0);
  m.crossed.assign(size_t(n_rays), 0);
  for (int r = 0; r < n_rays; ++r) {
    const size_t b = size_t(r) * S;
    double acc = 0;
    m.depth[size_t(r)] = t[b + S - 1];
    for (int i = 0; i < S; ++i) {
      if (acc + w[b + i] >= 0.5) {
        const double delta = i + 1 < S ? double(t[b + i + 1]) - t[b + i] : last_delta;
        const double T = 1.0 - acc, alpha = std::min(1.0 - 1e-12, w[b + i] / T);
        const double frac = std::clamp(std::log(2.0 * T) / -std::log1p(-alpha), 0.0, 1.0);
        m.index[size_t(r)] = i;
        m.before[size_t(r)] = acc;
        m.depth[size_t(r)] = t[b + i] + frac * delta;
        m.crossed[size_t(r)] = 1;
        break;
      }
      acc += w[b + i];
    }
  }
  return m;
}

// render_depth_spread in double: per ray (opacity A = Σ w, Σ w (t − m)² / A with m = Σ w t / A).
inline std::vector<double> ref_depth_spread(int n_rays, int S, const Vec<float>& t,
                                            const Vec<float>& w) {
  std::vector<double> out(size_t(n_rays) * 2, 0.0);
  for (int r = 0; r < n_rays; ++r) {
    double a = 0, m = 0, v = 0;
    for (int i = 0; i < S; ++i) a += w[size_t(r) * S + i], m += double(w[size_t(r) * S + i]) * t[size_t(r) * S + i];
    if (a >= 1e-12) {
      m /= a;
      for (int i = 0; i < S; ++i) {
        const double e = double(t[size_t(r) * S + i]) - m;
        v += w[size_t(r) * S + i] * e * e;
      }
      v /= a;
    }
    out[2 * size_t(r)] = a;
    out[2 * size_t(r) + 1] = v;
  }
  return out;
}

// render_volume_bwd, written independently of the kernel: dL/dτ_i by explicit suffix sums.
template <typename T>
void ref_volume_bwd(int n_rays, int S, T last_delta, const Vec<T>& t, const Vec<T>& h0,
                    const Vec<T>& head, const Vec<T>& grad_out, Vec<T>& grad_h0,
                    Vec<T>& grad_head) {
  Vec<T> out, w;
  ref_volume_fwd(n_rays, S, last_delta, t, h0, head, out, w);
  grad_h0.assign(size_t(n_rays) * S, T(0));
  grad_head.assign(size_t(n_rays) * S * 2, T(0));
  for (int r = 0; r < n_rays; ++r) {
    const T* g = &grad_out[3 * r];
    // suffix[i] = Σ_{k>i} w_k (g·c_k)
    Vec<T> gc(S), suffix(S + 1, T(0));
    for (int i = 0; i < S; ++i) {
      const size_t s = size_t(r) * S + i;
      gc[i] = g[0] * t[s] + g[1] * ref_sigmoid(head[2 * s]) + g[2] * ref_sigmoid(head[2 * s + 1]);
    }
    for (int i = S - 1; i >= 0; --i) suffix[i] = suffix[i + 1] + w[size_t(r) * S + i] * gc[i];
    T trans = 1;
    for (int i = 0; i < S; ++i) {
      const size_t s = size_t(r) * S + i;
      const T delta = i + 1 < S ? t[s + 1] - t[s] : last_delta;
      const T e = std::exp(-std::exp(std::min(h0[s], T(80))) * delta);
      trans *= e;  // T_{i+1}
      const T g_tau = trans * gc[i] - suffix[i + 1];
      grad_h0[s] = g_tau * delta * std::exp(std::clamp(h0[s], T(-15), T(15)));
      const T sp = ref_sigmoid(head[2 * s]), si = ref_sigmoid(head[2 * s + 1]);
      grad_head[2 * s] = g[1] * w[s] * sp * (T(1) - sp);
      grad_head[2 * s + 1] = g[2] * w[s] * si * (T(1) - si);
    }
  }
}

// render_raygrad_reduce
template <typename T>
void ref_raygrad(int n_rays, int S, const Vec<T>& t, const Vec<T>& grad_x, Vec<T>& grad_o,
                 Vec<T>& grad_d) {
  grad_o.assign(size_t(n_rays) * 3, T(0));
  grad_d.assign(size_t(n_rays) * 3, T(0));
  for (int r = 0; r < n_rays; ++r)
    for (int i = 0; i < S; ++i) {
      const size_t s = size_t(r) * S + i;
      for (int c = 0; c < 3; ++c) {
        grad_o[3 * r + c] += grad_x[3 * s + c];
        grad_d[3 * r + c] += t[s] * grad_x[3 * s + c];
      }
    }
}

// render_raygrad_reduce_rows: rows offset[r] + i (i < count[r]) of grad_x, t/o/d in the full
// R × M layout; components of x = o + t d outside [−bound, bound] are skipped.
template <typename T>
void ref_raygrad_rows(int n_rays, int M, T bound, const std::vector<int>& offset, const Vec<T>& t,
                      const Vec<T>& o, const Vec<T>& d, const Vec<T>& grad_x, Vec<T>& grad_o,
                      Vec<T>& grad_d) {
  grad_o.assign(size_t(n_rays) * 3, T(0));
  grad_d.assign(size_t(n_rays) * 3, T(0));
  for (int r = 0; r < n_rays; ++r)
    for (int i = 0; i < offset[size_t(r) + 1] - offset[size_t(r)]; ++i) {
      const size_t row = size_t(offset[size_t(r)] + i), s = size_t(r) * M + size_t(i);
      for (int c = 0; c < 3; ++c) {
        const T x = o[3 * size_t(r) + c] + t[s] * d[3 * size_t(r) + c];
        if (std::abs(x) > bound) continue;
        grad_o[3 * size_t(r) + c] += grad_x[3 * row + c];
        grad_d[3 * size_t(r) + c] += t[s] * grad_x[3 * row + c];
      }
    }
}

// render_loss_range: returns the batch-mean terms (depth, ret, intensity) and its gradient;
// `smooth`: the return term's target is the label clamped to [smooth, 1 − smooth].
template <typename T>
std::array<T, 3> ref_range_loss(int n, T a_d, T a_r, T a_i, const Vec<T>& out, const Vec<T>& target,
                                Vec<T>& grad_out, T smooth = T(0)) {
  std::array<T, 3> L{0, 0, 0};
  grad_out.assign(size_t(n) * 3, T(0));
  const T inv_n = T(1) / T(n);
  for (int r = 0; r < n; ++r) {
    const T m = target[3 * r + 2];
    const T e_d = m * (out[3 * r] - target[3 * r]);
    const T e_r = out[3 * r + 1] - std::min(std::max(m, smooth), T(1) - smooth);
    const T e_i = m * (out[3 * r + 2] - target[3 * r + 1]);
    L[0] += a_d * std::abs(e_d) * inv_n;
    L[1] += a_r * e_r * e_r * inv_n;
    L[2] += a_i * e_i * e_i * inv_n;
    grad_out[3 * r] = inv_n * a_d * m * T((e_d > 0) - (e_d < 0));
    grad_out[3 * r + 1] = inv_n * 2 * a_r * e_r;
    grad_out[3 * r + 2] = inv_n * 2 * a_i * m * e_i;
  }
  return L;
}

// render_loss_patchgrad: loss and its depth gradient ADDED to grad_out[3r] (pair by pair).
template <typename T>
T ref_patch_grad_loss(int n_patches, int R, int C, bool l1, T a_g, T inv_scale, T clip,
                      const Vec<T>& out, const Vec<T>& target, Vec<T>& grad_out) {
  const T inv_pairs = T(1) / (T(n_patches) * (R * (C - 1) + (R - 1) * C));
  T loss = 0;
  auto pair = [&](size_t a, size_t b) {
    const T dg = (target[3 * b] - target[3 * a]) * inv_scale;
    const T dp = (out[3 * b] - out[3 * a]) * inv_scale;
    const T m = target[3 * a + 2] * target[3 * b + 2] * (std::abs(dg) < clip ? T(1) : T(0));
    const T e = m * (dp - dg);
    loss += a_g * (l1 ? std::abs(e) : e * e) * inv_pairs;
    const T drho = l1 ? T((e > 0) - (e < 0)) : 2 * e;
    const T g = inv_pairs * a_g * drho * m * inv_scale;
    grad_out[3 * b] += g;
    grad_out[3 * a] -= g;
  };
  for (int p = 0; p < n_patches; ++p)
    for (int row = 0; row < R; ++row)
      for (int col = 0; col < C; ++col) {
        const size_t r = size_t(p) * R * C + row * C + col;
        if (col + 1 < C) pair(r, r + 1);
        if (row + 1 < R) pair(r, r + C);
      }
  return loss;
}

template <typename To, typename From>
Vec<To> cast_vec(const Vec<From>& v) {
  return Vec<To>(v.begin(), v.end());
}

// Central differences in double of L = g · out(h0, head), out from ref_volume_fwd: dL/dh0 (one
// per sample) and dL/dhead (two per sample), for the volume backward's gradient tests.
inline void fd_volume_grads(int n_rays, int S, double last_delta, const Vec<float>& t,
                            const Vec<float>& h0, const Vec<float>& head, const Vec<float>& g,
                            Vec<float>& fd_h0, Vec<float>& fd_head) {
  using D = Vec<double>;
  const D td = cast_vec<double>(t), gd = cast_vec<double>(g);
  D hd = cast_vec<double>(h0), headd = cast_vec<double>(head);
  auto loss = [&]() {
    D out, w;
    ref_volume_fwd<double>(n_rays, S, last_delta, td, hd, headd, out, w);
    double l = 0;
    for (size_t i = 0; i < out.size(); ++i) l += gd[i] * out[i];
    return l;
  };
  auto fd = [&](D& v, size_t i) {
    const double eps = 1e-6, keep = v[i];
    v[i] = keep + eps;
    const double lp = loss();
    v[i] = keep - eps;
    const double lm = loss();
    v[i] = keep;
    return float((lp - lm) / (2 * eps));
  };
  fd_h0.assign(td.size(), 0.0f);
  fd_head.assign(2 * td.size(), 0.0f);
  for (size_t i = 0; i < td.size(); ++i) fd_h0[i] = fd(hd, i);
  for (size_t i = 0; i < 2 * td.size(); ++i) fd_head[i] = fd(headd, i);
}

}  // namespace sgnlf::test
