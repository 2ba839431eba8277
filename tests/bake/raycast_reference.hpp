// Host reference of kernels/bake/raycast.cl (one ray at a time, the kernel's arithmetic in
// float): the brick DDA, the sample lattice t_k = near + k·step, the trilinear lookup and the
// volume rendering with early termination, and the weight's quartile depths. Tests only.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "bake/baked_scene.hpp"

namespace sgnlf::test {

// depth, return probability, intensity, opacity, the depths where 1 − T first reaches 1/8, 3/8,
// 5/8, 7/8 (−1: not reached), the median depth and the depth variance: bake::RayCaster's outputs.
inline std::array<float, 10> raycast_reference(const bake::BakedScene& s, const float* o_w,
                                              const float* d) {
  const auto inv = [](float v) { return std::fabs(v) > 1e-12f ? 1.0f / v : 1e30f; };
  const float o[3] = {o_w[0] - float(s.origin_m[0]), o_w[1] - float(s.origin_m[1]),
                      o_w[2] - float(s.origin_m[2])};
  const float id[3] = {inv(d[0]), inv(d[1]), inv(d[2])};
  const float bm = s.voxel_m * float(s.brick), inv_voxel = 1.0f / s.voxel_m;
  const int n1 = s.brick + 1, V = n1 * n1 * n1;
  float t0 = s.near_m, t1 = s.far_m;
  for (int a = 0; a < 3; ++a) {
    const float ta = -o[a] * id[a], tb = (float(s.dims[size_t(a)]) * bm - o[a]) * id[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  float depth = 0.0f, prob = 0.0f, inten = 0.0f, trans = 1.0f;
  float q[4] = {-1.0f, -1.0f, -1.0f, -1.0f};
  int lev = 0;
  float median = -1.0f, last_t = 0.0f, t_ref = -1.0f, m1 = 0.0f, m2 = 0.0f;
  const auto result = [&] {
    const float a = 1.0f - trans;
    float var = 0.0f;
    if (a >= 1e-12f) {
      const float mean = m1 / a;
      var = std::max(m2 / a - mean * mean, 0.0f);
    }
    return std::array<float, 10>{depth, prob, inten, a, q[0], q[1], q[2], q[3],
                                 median >= 0.0f ? median : last_t, var};
  };
  if (!(t0 < t1)) return result();
  int c[3], st[3];
  float tm[3], dd[3];
  for (int a = 0; a < 3; ++a) {
    c[a] = std::clamp(int(std::floor((o[a] + d[a] * t0) / bm)), 0, s.dims[size_t(a)] - 1);
    st[a] = d[a] >= 0.0f ? 1 : -1;
    tm[a] = (float(c[a] + (st[a] > 0)) * bm - o[a]) * id[a];
    dd[a] = std::fabs(bm * id[a]);
  }
  float tin = t0;
  for (;;) {
    const float tout = std::min(std::min(std::min(tm[0], tm[1]), tm[2]), t1);
    const int slot = s.index[size_t((c[2] * s.dims[1] + c[1]) * s.dims[0] + c[0])];
    if (slot >= 0) {
      const float hi = float(s.brick) - 1e-3f;
      int k = int(std::ceil((tin - s.near_m) / s.step_m));
      float t = s.near_m + float(k) * s.step_m;
      while (t < tout) {
        float u[3];
        int i[3];
        float f[3];
        for (int a = 0; a < 3; ++a) {
          u[a] = std::clamp((o[a] + d[a] * t) * inv_voxel - float(c[a] * s.brick), 0.0f, hi);
          i[a] = int(u[a]);
          f[a] = u[a] - float(i[a]);
        }
        // The kernel's cell mask: skipped when all 8 vertices lie below skip_logit.
        bool on = false;
        for (int q = 0; q < 8 && !on; ++q)
          on = s.vertices[size_t(slot * V + ((i[2] + (q >> 2)) * n1 + i[1] + ((q >> 1) & 1)) * n1 +
                                 i[0] + (q & 1))]
                   .logit >= s.skip_logit;
        if (!on) {
          ++k;
          t = s.near_m + float(k) * s.step_m;
          continue;
        }
        float val[3] = {0, 0, 0};
        for (int q = 0; q < 8; ++q) {
          const int dx = q & 1, dy = (q >> 1) & 1, dz = (q >> 2) & 1;
          const float w = (dx ? f[0] : 1 - f[0]) * (dy ? f[1] : 1 - f[1]) * (dz ? f[2] : 1 - f[2]);
          const bake::BakedVertex& v =
              s.vertices[size_t(slot * V + ((i[2] + dz) * n1 + i[1] + dy) * n1 + i[0] + dx)];
          val[0] += w * v.logit, val[1] += w * v.ret, val[2] += w * v.intensity;
        }
        const float e = std::exp(-std::exp(std::min(val[0], 80.0f)) * s.step_m);
        const float w = trans * (1.0f - e);
        depth += w * t, prob += w * val[1], inten += w * val[2];
        if (t_ref < 0.0f) t_ref = t;
        m1 += w * (t - t_ref);
        m2 += w * (t - t_ref) * (t - t_ref);
        last_t = t;
        if (median < 0.0f && trans * e <= 0.5f) {
          const float tau = -std::log1p(-std::min(1.0f - e, 1.0f - 1e-7f));
          median = t + std::min(std::max(std::log(2.0f * trans) / tau, 0.0f), 1.0f) * s.step_m;
        }
        trans *= e;
        while (lev < 4 && 1.0f - trans >= float(2 * lev + 1) * 0.125f) q[lev++] = t;
        if (trans < s.stop_transmittance) return result();
        ++k;
        t = s.near_m + float(k) * s.step_m;
      }
    }
    if (tout >= t1) break;
    const int a = tm[0] <= tm[1] && tm[0] <= tm[2] ? 0 : (tm[1] <= tm[2] ? 1 : 2);
    c[a] += st[a], tm[a] += dd[a];
    if (c[a] < 0 || c[a] >= s.dims[size_t(a)]) break;
    tin = tout;
  }
  return result();
}

}  // namespace sgnlf::test
