// OccupancyGrid: building from a density callback, dilation, lookups (see occupancy_grid.hpp).
#include "render/occupancy_grid.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace sgnlf::render {

std::vector<uint8_t> dilate_cells(const std::vector<uint8_t>& cells, std::array<int, 3> dims,
                                  int steps) {
  const int nx = dims[0], ny = dims[1], nz = dims[2];
  std::vector<uint8_t> cur = cells, next(cells.size());
  const auto at = [&](int i, int j, int k) { return (size_t(k) * size_t(ny) + size_t(j)) * size_t(nx) + size_t(i); };
  for (int step = 0; step < steps; ++step) {
    // Separable: the 3³ max filter is three 3-wide filters, one per axis.
    for (int axis = 0; axis < 3; ++axis) {
      for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
          for (int i = 0; i < nx; ++i) {
            const int c[3] = {i, j, k}, n[3] = {nx, ny, nz};
            uint8_t v = cur[at(i, j, k)];
            for (int d = -1; d <= 1 && !v; d += 2) {
              int q[3] = {c[0], c[1], c[2]};
              q[axis] += d;
              if (q[axis] >= 0 && q[axis] < n[axis]) v = cur[at(q[0], q[1], q[2])];
            }
            next[at(i, j, k)] = v ? 1 : 0;
          }
      cur.swap(next);
    }
  }
  return cur;
}

OccupancyGrid::OccupancyGrid(cl::Runtime& rt, const GridBox& box, std::array<int, 3> dims,
                             std::vector<uint8_t> cells)
    : box_(box), dims_(dims), cells_(std::move(cells)) {
  const size_t n = size_t(dims[0]) * size_t(dims[1]) * size_t(dims[2]);
  require(dims[0] > 0 && dims[1] > 0 && dims[2] > 0 && cells_.size() == n,
          "OccupancyGrid: " + std::to_string(cells_.size()) + " cells for dims " +
              std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " +
              std::to_string(dims[2]));
  for (int a = 0; a < 3; ++a)
    require(box.hi[size_t(a)] > box.lo[size_t(a)], "OccupancyGrid: empty box along axis " + std::to_string(a));
  buf_ = cl::Buffer(rt, std::max<size_t>(n, 1));
  buf_.write(cells_.data(), n);
}

OccupancyGrid::OccupancyGrid(const GridBox& box, std::array<int, 3> dims) : box_(box), dims_(dims) {}

std::array<float, 3> OccupancyGrid::cell_size() const {
  std::array<float, 3> c{};
  for (size_t a = 0; a < 3; ++a) c[a] = (box_.hi[a] - box_.lo[a]) / float(dims_[a]);
  return c;
}

size_t OccupancyGrid::occupied() const {
  return size_t(std::count_if(cells_.begin(), cells_.end(), [](uint8_t v) { return v != 0; }));
}

long OccupancyGrid::cell_of(float x, float y, float z) const {
  // The kernel's arithmetic (kernels/pipeline/fast_march.cl, fast_cell): (x − lo)·(1/cell).
  const cl_float4 lo = lo4(), inv = inv_cell4();
  const float u[3] = {(x - lo.s[0]) * inv.s[0], (y - lo.s[1]) * inv.s[1], (z - lo.s[2]) * inv.s[2]};
  int c[3];
  for (int a = 0; a < 3; ++a) {
    if (!(u[a] >= 0.0f && u[a] <= float(dims_[size_t(a)]))) return -1;
    c[a] = std::min(int(u[a]), dims_[size_t(a)] - 1);
  }
  const int i = c[0], j = c[1], k = c[2];
  return (long(k) * dims_[1] + j) * dims_[0] + i;
}

cl_float4 OccupancyGrid::lo4() const {
  cl_float4 v;
  for (int a = 0; a < 3; ++a) v.s[a] = box_.lo[size_t(a)];
  v.s[3] = 0.0f;
  return v;
}

cl_float4 OccupancyGrid::inv_cell4() const {
  const auto c = cell_size();
  cl_float4 v;
  for (int a = 0; a < 3; ++a) v.s[a] = 1.0f / c[size_t(a)];
  v.s[3] = 0.0f;
  return v;
}

cl_int4 OccupancyGrid::dims4() const {
  cl_int4 v;
  for (int a = 0; a < 3; ++a) v.s[a] = dims_[size_t(a)];
  v.s[3] = 0;
  return v;
}

OccupancyGrid OccupancyGrid::build(cl::Runtime& rt, const FastRenderConfig& cfg,
                                   const GridBox& box_in, float scene_scale, float delta,
                                   const DensityFn& density, int batch,
                                   const std::vector<float>& points) {
  cfg.validate();
  require(scene_scale > 0.0f && delta > 0.0f && batch > 0,
          "OccupancyGrid::build: scale, delta and batch must be positive");
  const auto t0 = std::chrono::steady_clock::now();
  const float cell = cfg.cell_m * scene_scale, margin = cfg.margin_m * scene_scale;
  GridBox box;
  std::array<int, 3> dims{};
  double n_cells = 1.0;
  for (size_t a = 0; a < 3; ++a) {
    const float lo = box_in.lo[a] - margin, hi = box_in.hi[a] + margin;
    require(hi > lo, "OccupancyGrid::build: empty box along axis " + std::to_string(a));
    dims[a] = std::max(1, int(std::ceil((hi - lo) / cell)));
    box.lo[a] = lo;
    box.hi[a] = lo + float(dims[a]) * cell;
    n_cells *= double(dims[a]);
  }
  if (n_cells > double(cfg.max_cells))
    throw ConfigError("fast_render: an occupancy grid of " + std::to_string(dims[0]) + " x " +
                      std::to_string(dims[1]) + " x " + std::to_string(dims[2]) +
                      " cells of 'cell_m' = " + std::to_string(cfg.cell_m) +
                      " m exceeds 'max_cells' = " + std::to_string(cfg.max_cells));
  // Occupied when exp(h0)·δ > −log(1 − alpha), i.e. h0 > log(−log(1 − alpha)/δ).
  const float h0_min = float(std::log(-std::log1p(-double(cfg.alpha)) / double(delta)));
  const int P = cfg.probes_per_axis, per_cell = P * P * P;
  const size_t total = size_t(n_cells);
  std::vector<uint8_t> cells(total, 0);
  const size_t cells_per_call = std::max<size_t>(1, size_t(batch) / size_t(per_cell));
  std::vector<float> x;
  for (size_t c0 = 0; c0 < total; c0 += cells_per_call) {
    const size_t c1 = std::min(total, c0 + cells_per_call);
    x.assign((c1 - c0) * size_t(per_cell) * 3, 0.0f);
    size_t p = 0;
    for (size_t c = c0; c < c1; ++c) {
      const size_t i = c % size_t(dims[0]), j = (c / size_t(dims[0])) % size_t(dims[1]),
                   k = c / (size_t(dims[0]) * size_t(dims[1]));
      const size_t idx[3] = {i, j, k};
      for (int pz = 0; pz < P; ++pz)
        for (int py = 0; py < P; ++py)
          for (int px = 0; px < P; ++px, ++p) {
            const int pr[3] = {px, py, pz};
            for (size_t a = 0; a < 3; ++a)
              x[3 * p + a] = box.lo[a] + (float(idx[a]) + (float(pr[a]) + 0.5f) / float(P)) * cell;
          }
    }
    const std::vector<float> h0 = density(x, int(p));
    require(h0.size() >= p, "OccupancyGrid::build: the density callback returned too few values");
    for (size_t c = c0; c < c1; ++c) {
      const float* h = &h0[(c - c0) * size_t(per_cell)];
      for (int q = 0; q < per_cell; ++q)
        if (h[q] > h0_min) {
          cells[c] = 1;
          break;
        }
    }
  }
  // The returns' cells: the same rule as the lookup (cell_of) on a grid of these dims.
  const OccupancyGrid shape(box, dims);
  for (size_t p = 0; p + 2 < points.size(); p += 3) {
    const long c = shape.cell_of(points[p], points[p + 1], points[p + 2]);
    if (c >= 0) cells[size_t(c)] = 1;
  }
  OccupancyGrid g(rt, box, dims, dilate_cells(cells, dims, cfg.dilate));
  g.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return g;
}

}  // namespace sgnlf::render
