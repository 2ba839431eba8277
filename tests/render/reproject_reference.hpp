// Host reference of kernels/render/reproject.cl (tests only; the runtime never calls it).
// Templated on the scalar: the float version repeats the kernels' arithmetic operation by
// operation (same order, no contraction into FMA) and must agree with the device bit for bit
// on D_ij, M_ij and the winners; the double version serves the finite-difference tests. The
// first guess of a pixel uses std::atan2 where the kernel uses a polynomial: the boundary walk
// ends in the same pixel from any guess, and the tests rely on that.
#pragma once
#if defined(__clang__)
#pragma clang fp contract(off)
#endif
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "geometry/pixel_boundaries.hpp"
#include "geometry/range_image.hpp"
#include "geometry/se3.hpp"

namespace sgnlf::test {

// Everything the projection needs, in the scalar T.
template <typename T>
struct RefReprojGeometry {
  int Hi = 0, Wi = 0, Hj = 0, Wj = 0;
  std::vector<T> dirs;      // frame i's pixel directions (the float table the device uses)
  std::vector<T> col, row;  // frame j's pixel boundaries
  T min_q = 0, max_q = 0, fov_up_rad = 0, inv_row_step = 0;
};

template <typename T>
RefReprojGeometry<T> ref_reproj_geometry(const Sensor& si, const Sensor& sj, double range_scale) {
  RefReprojGeometry<T> g;
  g.Hi = si.height, g.Wi = si.width, g.Hj = sj.height, g.Wj = sj.width;
  const auto d = ray_directions(si);
  g.dirs.assign(d.begin(), d.end());
  const PixelBoundaries b = pixel_boundaries(sj);
  g.col.assign(b.col.begin(), b.col.end());
  g.row.assign(b.row.begin(), b.row.end());
  const double lo = sj.min_range_m * range_scale, hi = sj.max_range_m * range_scale;
  g.min_q = T(lo * lo);
  g.max_q = T(hi * hi);
  g.fov_up_rad = T(sj.fov_up_deg * M_PI / 180.0);
  g.inv_row_step = T(sj.height / (sj.fov_deg * M_PI / 180.0));
  return g;
}

// T_lidarj_lidari as rows (R_k0, R_k1, R_k2, t_k) in T.
template <typename T>
std::array<T, 12> ref_rows(const Pose& T_lidarj_lidari) {
  std::array<T, 12> r{};
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 4; ++c) r[size_t(4 * k + c)] = T(T_lidarj_lidari.matrix()(k, c));
  return r;
}

template <typename T>
void ref_transform(const std::array<T, 12>& m, const T x[3], T y[3]) {
  for (int k = 0; k < 3; ++k) {
    T acc = m[size_t(4 * k)] * x[0];
    acc = acc + m[size_t(4 * k + 1)] * x[1];
    acc = acc + m[size_t(4 * k + 2)] * x[2];
    y[k] = acc + m[size_t(4 * k + 3)];
  }
}

template <typename T>
bool ref_above_col(const std::vector<T>& col, int k, T x, T y) {
  const T a = col[size_t(2 * k)] * y;
  const T b = col[size_t(2 * k + 1)] * x;
  return a - b > T(0);
}

template <typename T>
bool ref_above_row(const std::vector<T>& row, int k, T z, T qxy) {
  const T c = row[size_t(2 * (k + 1))], s = row[size_t(2 * (k + 1) + 1)];
  const T a = z * c;
  const T s2 = s * s;
  const T b2 = qxy * s2;
  const T a2 = a * a;
  if (s > T(0)) return a > T(0) && a2 > b2;
  return a > T(0) || a2 < b2;
}

// The boundary walk from the guess c (clamped to [0, W]).
template <typename T>
int ref_column_from(const std::vector<T>& col, int W, T x, T y, int c) {
  c = std::min(std::max(c, 0), W);
  if (c < W && !ref_above_col(col, c, x, y)) {
    do ++c;
    while (c < W && !ref_above_col(col, c, x, y));
  } else {
    while (c > 0 && ref_above_col(col, c - 1, x, y)) --c;
  }
  return c;
}

template <typename T>
int ref_column(const std::vector<T>& col, int W, T x, T y) {
  const T u = (T(M_PI) - std::atan2(y, x)) * (T(W) / (T(2) * T(M_PI)));
  return ref_column_from(col, W, x, y, int(std::floor(u + T(0.5))));
}

template <typename T>
int ref_row_from(const RefReprojGeometry<T>& g, T z, T qxy, int r) {
  r = std::min(std::max(r, -1), g.Hj);
  if (r < g.Hj && !ref_above_row(g.row, r, z, qxy)) {
    do ++r;
    while (r < g.Hj && !ref_above_row(g.row, r, z, qxy));
  } else {
    while (r > -1 && ref_above_row(g.row, r - 1, z, qxy)) --r;
  }
  return r;
}

template <typename T>
int ref_row(const RefReprojGeometry<T>& g, T z, T qxy) {
  const T alpha = std::atan2(z, std::sqrt(qxy));
  return ref_row_from(g, z, qxy, int(std::floor((g.fov_up_rad - alpha) * g.inv_row_step + T(0.5))));
}

// Target pixel of source pixel p at depth d (−1 = none), and q = ||y||².
template <typename T>
int ref_target(const RefReprojGeometry<T>& g, const std::array<T, 12>& m, int p, T d, T* q_out) {
  if (!(d > T(0)) || std::isinf(d)) return -1;
  const T x[3] = {d * g.dirs[3 * size_t(p)], d * g.dirs[3 * size_t(p) + 1],
                  d * g.dirs[3 * size_t(p) + 2]};
  T y[3];
  ref_transform(m, x, y);
  const T qxy = y[0] * y[0] + y[1] * y[1];
  const T q = qxy + y[2] * y[2];
  *q_out = q;
  if (q >= g.max_q || q <= g.min_q) return -1;
  const int r = ref_row(g, y[2], qxy);
  if (r < 0 || r >= g.Hj) return -1;
  const int c = ref_column(g.col, g.Wj, y[0], y[1]);
  if (c >= g.Wj) return -1;
  return r * g.Wj + c;
}

template <typename T>
struct RefReprojection {
  std::vector<T> range, mask;
  std::vector<int> winner;
};

// Sequential z-buffer over the sources in index order: a strictly smaller q replaces, so ties
// keep the smallest source index.
template <typename T>
RefReprojection<T> ref_reproject_forward(const RefReprojGeometry<T>& g, const std::vector<T>& depth,
                                         const std::array<T, 12>& m) {
  const size_t n_dst = size_t(g.Hj) * g.Wj;
  RefReprojection<T> out{std::vector<T>(n_dst, T(0)), std::vector<T>(n_dst, T(0)),
                         std::vector<int>(n_dst, -1)};
  std::vector<T> best(n_dst, std::numeric_limits<T>::infinity());
  for (int p = 0; p < g.Hi * g.Wi; ++p) {
    T q = 0;
    const int t = ref_target(g, m, p, depth[size_t(p)], &q);
    if (t < 0) continue;
    if (out.winner[size_t(t)] < 0 || q < best[size_t(t)]) {
      best[size_t(t)] = q;
      out.winner[size_t(t)] = p;
    }
  }
  for (size_t t = 0; t < n_dst; ++t)
    if (out.winner[t] >= 0) {
      out.range[t] = std::sqrt(best[t]);
      out.mask[t] = T(1);
    }
  return out;
}

// Backward through the winners: dL/dd per source and S_m = Σ g·m, S_xm = Σ g·(x × m), with
// n = y/||y|| and m = Rᵀ n (in double).
struct RefReprojBackward {
  std::vector<double> grad_depth;
  Vec3 s_m = Vec3::Zero(), s_xm = Vec3::Zero();
};

inline RefReprojBackward ref_reproject_backward(const RefReprojGeometry<double>& g,
                                                const std::vector<double>& depth,
                                                const Pose& T_lidarj_lidari,
                                                const std::vector<int>& winner,
                                                const std::vector<double>& grad_range) {
  RefReprojBackward b;
  b.grad_depth.assign(depth.size(), 0.0);
  const Mat3 R = T_lidarj_lidari.linear();
  for (size_t t = 0; t < winner.size(); ++t) {
    const int w = winner[t];
    if (w < 0) continue;
    const Vec3 v(g.dirs[3 * size_t(w)], g.dirs[3 * size_t(w) + 1], g.dirs[3 * size_t(w) + 2]);
    const Vec3 x = depth[size_t(w)] * v;
    const Vec3 y = T_lidarj_lidari * x;
    const Vec3 m = R.transpose() * (y / y.norm());
    b.grad_depth[size_t(w)] = grad_range[t] * m.dot(v);
    b.s_m += grad_range[t] * m;
    b.s_xm += grad_range[t] * x.cross(m);
  }
  return b;
}

// dL/dξ of both frames from the sums (right perturbations mapped to ξ = (ω, u), se3.hpp).
inline std::pair<Vec6, Vec6> ref_reproject_xi_gradient(const RefReprojBackward& b,
                                                       const Pose& T_lidarj_lidari,
                                                       const Vec6& xi_i, const Vec6& xi_j) {
  Vec6 gi, gj;
  gi.head<3>() = right_jacobian_so3(xi_i.head<3>()).transpose() * b.s_xm;
  gi.tail<3>() = exp_so3(xi_i.head<3>()) * b.s_m;
  gj.head<3>() = Vec3::Zero();
  gj.tail<3>() = -(exp_so3(xi_j.head<3>()) * (T_lidarj_lidari.linear() * b.s_m));
  return {gi, gj};
}

}  // namespace sgnlf::test
