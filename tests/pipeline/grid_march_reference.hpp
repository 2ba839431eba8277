// Host reference of the fast renderer's grid-placed marching (kernels/pipeline/grid_march.cl,
// pipeline::GridMarch): the lattice walk, the waves and their termination, the compositing, the
// median and the head threshold, written plainly, one ray at a time.
#pragma once
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "render/occupancy_grid.hpp"

namespace sgnlf::test {

struct MarchSample {
  float t, dt, x[3];
  int k;
  bool in_cell;
};

struct MarchLattice {
  float near, h, bound;
  int m, K, mc;  // mc: the coarse step in occupied cells, in fine steps
};

// One step of the walk at lattice point k (the kernel's gm_step): true with the sample when k is
// evaluated, false when it lies in a free cell (k then jumps past that cell). Occupied cells
// step by 1 in fine mode, by m in coarse mode, as outside the box.
inline bool march_step(int& k, bool fine, const float o[3], const float d[3],
                       const MarchLattice& L, const render::OccupancyGrid& g, MarchSample& s) {
  const float t = L.near + (float(k) + 0.5f) * L.h;
  const float x[3] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
  const bool in_bound = std::fabs(x[0]) <= L.bound && std::fabs(x[1]) <= L.bound &&
                        std::fabs(x[2]) <= L.bound;
  const long c = in_bound ? g.cell_of(x[0], x[1], x[2]) : -1;
  if (c >= 0 && !g.cells()[size_t(c)]) {
    const auto dims = g.dims();
    const long idx[3] = {c % dims[0], (c / dims[0]) % dims[1], c / (long(dims[0]) * dims[1])};
    const cl_float4 lo = g.lo4(), inv = g.inv_cell4();
    float t_exit = INFINITY;
    for (int a = 0; a < 3; ++a) {
      if (d[a] == 0.0f) continue;
      const float cell = 1.0f / inv.s[a];
      const float lo_a = lo.s[a] + float(idx[a]) * cell;
      t_exit = std::min(t_exit, ((d[a] > 0.0f ? lo_a + cell : lo_a) - o[a]) / d[a]);
    }
    const float kf = std::floor((t_exit - L.near) / L.h - 0.5f) + 1.0f;
    k = kf > float(k) ? (kf < float(L.K) ? int(kf) : L.K) : k + 1;
    return false;
  }
  const int step = c < 0 ? L.m : fine ? 1 : L.mc;
  s.k = k;
  s.in_cell = c >= 0;
  s.t = t;
  s.dt = float(step) * L.h;
  for (int a = 0; a < 3; ++a) s.x[a] = std::clamp(x[a], -L.bound, L.bound);
  k += step;
  return true;
}

struct MarchResult {
  std::vector<float> out;  // n × 3
  long evaluated = 0, head_rows = 0;
};

// σ logit at x; the head's logits (a, b) of a sample at x on ray r.
using MarchDensity = std::function<float(const float x[3])>;
using MarchHead = std::function<void(const float x[3], int r, float& a, float& b)>;

// Rays (o, d: n × 3) marched in waves of min(cap, wave) samples; a ray stops after the wave its transmittance fell below eps in. In coarse mode the
// first sample in an occupied cell with α ≥ hit is dropped with the rest of its wave and the ray
// rewinds to k − (m − 1) (at least one past its last composited sample) in fine mode; m fine
// samples in a row below hit turn it coarse after the wave.
inline MarchResult march_reference(const std::vector<float>& o, const std::vector<float>& d,
                                   int n, const MarchLattice& L, const render::OccupancyGrid& g,
                                   float eps, float thr, float hit, int wave, int cap, bool median, const MarchDensity& density,
                                   const MarchHead& head) {
  MarchResult res;
  res.out.assign(size_t(n) * 3, 0.0f);
  for (int r = 0; r < n; ++r) {
    const float* o3 = &o[3 * size_t(r)];
    const float* d3 = &d[3 * size_t(r)];
    int k = 0, quiet = 0, last_k = -1;
    bool fine = L.mc == 1 || hit <= 0.0f;
    float T = 1.0f, depth = 0.0f, prob = 0.0f, inten = 0.0f, med = -1.0f;
    while (k < L.K) {
      const int K_i = std::min(cap, wave);
      std::vector<MarchSample> samples;
      MarchSample s{};
      while (k < L.K && int(samples.size()) < K_i)
        if (march_step(k, fine, o3, d3, L, g, s)) samples.push_back(s);
      res.evaluated += long(samples.size());
      for (const MarchSample& q : samples) {
        const float e = std::exp(-std::exp(std::min(density(q.x), 80.0f)) * q.dt);
        if (!fine && L.mc > 1 && q.in_cell && 1.0f - e >= hit) {
          k = std::max(q.k - (L.mc - 1), last_k + 1);
          fine = true;
          quiet = 0;
          break;
        }
        if (fine) quiet = 1.0f - e < hit ? quiet + 1 : 0;
        last_k = q.k;
        const float w = T * (1.0f - e);
        if (med < 0.0f && (1.0f - T) + w >= 0.5f) {
          const float alpha = std::min(w / std::max(T, 1e-30f), 1.0f);
          const float tau = -std::log1p(-std::min(alpha, 1.0f - 1e-7f));
          med = q.t + std::min(std::max(std::log(2.0f * T) / tau, 0.0f), 1.0f) * q.dt;
        }
        depth += w * q.t;
        if (w > thr) {
          float a = 0.0f, b = 0.0f;
          head(q.x, r, a, b);
          prob += w / (1.0f + std::exp(-a));
          inten += w / (1.0f + std::exp(-b));
          ++res.head_rows;
        }
        T *= e;
      }
      if (fine && L.mc > 1 && hit > 0.0f && quiet >= L.mc) fine = false, quiet = 0;
      if (eps > 0.0f && T < eps) break;
    }
    const float t_last = L.near + (float(L.K) - 0.5f) * L.h;
    res.out[3 * size_t(r)] = median ? (med < 0.0f ? t_last : med) : depth;
    res.out[3 * size_t(r) + 1] = prob;
    res.out[3 * size_t(r) + 2] = inten;
  }
  return res;
}

}  // namespace sgnlf::test
