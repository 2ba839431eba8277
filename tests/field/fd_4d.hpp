// Finite-difference checks shared by the 4D encodings' tests (K-Planes, time-sliced hash
// grids): L = <enc(params, x, t), r> against the backward's parameter gradient and d_x. Both
// launchers take (params, offset, x, t, n, ...) in the same order.
#pragma once
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "cl/runtime.hpp"
#include "core/rng.hpp"
#include "field/hash_grid.hpp"
#include "support/test_device.hpp"

namespace sgnlf::test {

// n points in [−0.95, 0.95]³ whose every coordinate stays more than 4h (in grid cells) from
// the cell faces of every level, so a grid encoding is smooth around them.
inline std::vector<float> fd_points(const std::vector<field::HashGridLevel>& levels, int n,
                                    float h, uint64_t seed) {
  std::vector<float> x;
  Rng rng(seed);
  while (x.size() < size_t(n) * 3) {
    float p[3];
    bool ok = true;
    for (float& v : p) {
      v = rng.uniform(-0.95f, 0.95f);
      for (const auto& lv : levels) {
        const double pos = (v * 0.5 + 0.5) * lv.scale + 0.5, fr = pos - std::floor(pos);
        ok = ok && fr > 4 * h * lv.scale && fr < 1 - 4 * h * lv.scale;
      }
    }
    if (ok) x.insert(x.end(), p, p + 3);
  }
  return x;
}

inline double dot(const std::vector<float>& a, const std::vector<float>& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += double(a[i]) * b[i];
  return s;
}

// `x` must keep every coordinate more than a few `h` away from cell boundaries (the encodings
// are piecewise smooth); `stride`: every stride-th parameter with a non-zero gradient is checked.
template <class Encoding>
void check_4d_gradients(cl::Runtime& rt, Encoding& enc, const std::vector<float>& params,
                        const std::vector<float>& x, const std::vector<float>& t,
                        const std::vector<float>& r, int w, float h, size_t stride) {
  const int n = int(x.size() / 3);
  auto b_params = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, x);
  auto b_t = cl::Buffer::from(rt, t), b_r = cl::Buffer::from(rt, r);
  cl::Buffer b_enc(rt, size_t(n) * w * 4), b_grad(rt, params.size() * 4), b_dx(rt, size_t(n) * 12);
  enc.backward(b_params, 0, b_x, b_t, n, b_r, b_grad, 0, &b_dx);
  const auto grad = b_grad.read_vec<float>(params.size());
  const auto dx = b_dx.read_vec<float>(size_t(n) * 3);
  auto loss = [&](const std::vector<float>& p, const std::vector<float>& xs) {
    b_params.write_vec(p);
    b_x.write_vec(xs);
    enc.forward(b_params, 0, b_x, b_t, n, b_enc);
    return dot(b_enc.read_vec<float>(size_t(n) * w), r);
  };
  // Parameters: L is linear in each single parameter (one factor of a product), so central
  // differences are exact up to rounding.
  std::vector<float> fd, an;
  for (size_t k = 0; k < grad.size() && fd.size() < 60; k += stride) {
    if (grad[k] == 0.0f) continue;
    auto p = params;
    p[k] += 0.25f;
    const double lp = loss(p, x);
    p[k] -= 0.5f;
    fd.push_back(float((lp - loss(p, x)) / 0.5));
    an.push_back(grad[k]);
  }
  REQUIRE(fd.size() >= 30);
  CHECK(max_sym_rel_err(fd, an, 1e-3) < 1e-3);
  // Positions.
  fd.clear();
  an.clear();
  for (size_t k = 0; k < x.size(); ++k) {
    auto xp = x, xm = x;
    xp[k] += h;
    xm[k] -= h;
    fd.push_back(float((loss(params, xp) - loss(params, xm)) / (2.0 * h)));
    an.push_back(dx[k]);
  }
  CHECK(max_sym_rel_err(fd, an, 1e-1) < 1e-2);
}

}  // namespace sgnlf::test
