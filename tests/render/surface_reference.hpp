// Host references of kernels/render/surface.cl (tests only): the training samples placed by
// the return and the weight-carving loss with its gradient, written independently of the
// kernels (the carving gradient by an explicit double loop over dw_i/dh0_k).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "render_reference.hpp"

namespace sgnlf::test {

inline constexpr uint32_t kStreamSurface = 0x52454e33u;

inline bool ref_has_return(const Vec<float>& target, int r, float near) {
  return target[3 * size_t(r) + 2] > 0.5f && target[3 * size_t(r)] > near;
}

// render_sample_surface
inline void ref_sample_surface(int n_rays, int F, int B, int K, float near, float far,
                               float half_w, float behind, bool jitter, uint64_t seed,
                               uint32_t step, const Vec<float>& o, const Vec<float>& d,
                               const Vec<float>& target, Vec<float>& t, Vec<float>& x) {
  const int M = F + B + K;
  t.assign(size_t(n_rays) * M, 0.f);
  x.assign(t.size() * 3, 0.f);
  for (int r = 0; r < n_rays; ++r) {
    const float rr = target[3 * size_t(r)];
    const float a = std::clamp(rr - half_w, near, far), b = std::clamp(rr + half_w, near, far),
                c = std::clamp(rr + half_w + behind, near, far);
    const bool ret = ref_has_return(target, r, near);
    for (int i = 0; i < M; ++i) {
      const uint32_t g = uint32_t(r * ((M + 3) / 4) + i / 4);
      const float xi =
          jitter ? u32_to_unit_float(philox_block(seed, kStreamSurface, (uint64_t(step) << 32) | g)[i % 4])
                 : 0.5f;
      float v;
      if (!ret) v = near + (float(i) + xi) * ((far - near) / float(M));
      else if (i < F) v = near + (float(i) + xi) * ((a - near) / float(F));
      else if (i < F + B) v = a + (float(i - F) + xi) * ((b - a) / float(B));
      else if (i < M - 1) v = b + (float(i - F - B) + xi) * ((c - b) / float(K - 1));
      else v = (K > 1 ? c : b) + xi * (far - (K > 1 ? c : b));
      const size_t s = size_t(r) * M + i;
      t[s] = v;
      for (int k = 0; k < 3; ++k) x[3 * s + k] = o[3 * size_t(r) + k] + v * d[3 * size_t(r) + k];
    }
  }
}

// The carving loss of rays (n × M samples) as a function of h0 (renderer weights recomputed).
template <typename T>
T ref_carve_loss(int n_rays, int M, T last_delta, T near, T half_w, T scale, const Vec<T>& t,
                 const Vec<T>& h0, const Vec<float>& target, Vec<T>* terms = nullptr) {
  Vec<T> out, w, head(size_t(n_rays) * M * 2, T(0));
  ref_volume_fwd(n_rays, M, last_delta, t, h0, head, out, w);
  T total = 0;
  if (terms) terms->assign(size_t(n_rays), T(0));
  for (int r = 0; r < n_rays; ++r) {
    if (!(target[3 * size_t(r) + 2] > 0.5f && T(target[3 * size_t(r)]) > near)) continue;
    T l = 0;
    for (int i = 0; i < M; ++i) {
      const size_t s = size_t(r) * M + i;
      if (std::abs(t[s] - T(target[3 * size_t(r)])) > half_w) l += w[s] * w[s];
    }
    if (terms) (*terms)[size_t(r)] = scale * l;
    total += scale * l;
  }
  return total;
}

// dL/dh0 of ref_carve_loss by the chain rule over every (i, k) pair (O(M²) per ray), with
// the renderer's dσ/dh0 = exp(clamp(h0, -15, 15)).
template <typename T>
Vec<T> ref_carve_grad(int n_rays, int M, T last_delta, T near, T half_w, T scale, const Vec<T>& t,
                      const Vec<T>& h0, const Vec<float>& target) {
  Vec<T> out, w, head(size_t(n_rays) * M * 2, T(0));
  ref_volume_fwd(n_rays, M, last_delta, t, h0, head, out, w);
  Vec<T> g(size_t(n_rays) * M, T(0));
  for (int r = 0; r < n_rays; ++r) {
    if (!(target[3 * size_t(r) + 2] > 0.5f && T(target[3 * size_t(r)]) > near)) continue;
    const size_t b = size_t(r) * M;
    for (int k = 0; k < M; ++k) {
      const T dk = k + 1 < M ? t[b + k + 1] - t[b + k] : last_delta;
      T trans_after = 1;  // T_{k+1}
      for (int j = 0; j <= k; ++j) {
        const T dj = j + 1 < M ? t[b + j + 1] - t[b + j] : last_delta;
        trans_after *= std::exp(-std::exp(std::min(h0[b + j], T(80))) * dj);
      }
      T dl = 0;
      for (int i = k; i < M; ++i) {
        if (!(std::abs(t[b + i] - T(target[3 * size_t(r)])) > half_w)) continue;
        const T dw = i == k ? dk * trans_after : -dk * w[b + i];  // dw_i/dσ_k
        dl += T(2) * scale * w[b + i] * dw;
      }
      g[b + k] = dl * std::exp(std::clamp(h0[b + k], T(-15), T(15)));
    }
  }
  return g;
}

}  // namespace sgnlf::test
