// Occupancy grid of a trained field for the fast renderer (instant-ngp's density bitfield, one
// level): cells of a box in the normalised frame, a cell occupied when the field's density at
// any of its probe points could give a sample of the renderer a weight above a threshold, then
// dilated. Samples in free cells are not evaluated (zero density). Built on the host from a
// density callback, uploaded once; kernels/pipeline/fast_march.cl reads it.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "cl/runtime.hpp"
#include "render/fast_render_config.hpp"

namespace sgnlf::render {

struct GridBox {
  std::array<float, 3> lo{}, hi{};  // normalised frame
};

class OccupancyGrid {
 public:
  // σ logits (h0, σ = exp(h0)) at n points (n × 3, normalised frame).
  using DensityFn = std::function<std::vector<float>(const std::vector<float>& x, int n)>;

  // The box `box` (normalised) divided into cells of cfg.cell_m·scale; `delta` is the
  // renderer's bin width (normalised). `batch` = points per density call. ConfigError when
  // the grid would exceed cfg.max_cells.
  // Cells holding one of `points` (n × 3, normalised: the training returns) are occupied
  // whatever the probes found: thin structures between probes stay.
  static OccupancyGrid build(cl::Runtime& rt, const FastRenderConfig& cfg, const GridBox& box,
                             float scene_scale, float delta, const DensityFn& density,
                             int batch, const std::vector<float>& points = {});
  // A grid from given cells (tests): dims[0] × dims[1] × dims[2], x fastest.
  OccupancyGrid(cl::Runtime& rt, const GridBox& box, std::array<int, 3> dims,
                std::vector<uint8_t> cells);

  const std::array<int, 3>& dims() const { return dims_; }
  const GridBox& box() const { return box_; }
  std::array<float, 3> cell_size() const;
  const std::vector<uint8_t>& cells() const { return cells_; }
  size_t occupied() const;
  double occupied_fraction() const { return cells_.empty() ? 0.0 : double(occupied()) / double(cells_.size()); }
  // Host lookup (the kernel's rule): −1 outside the box, else the cell index (a point on an
  // upper face belongs to the last cell).
  long cell_of(float x, float y, float z) const;
  // Whether a sample at (x, y, z) is evaluated: its cell is occupied, or it lies outside the
  // box (where the grid knows nothing: the protocol renderer evaluates it there).
  bool occupied_at(float x, float y, float z) const {
    const long c = cell_of(x, y, z);
    return c < 0 || cells_[size_t(c)] != 0;
  }
  const cl::Buffer& device() const { return buf_; }
  // Kernel arguments: lo, 1/cell, dims (float4, float4, int4).
  cl_float4 lo4() const;
  cl_float4 inv_cell4() const;
  cl_int4 dims4() const;
  // Seconds the build took (density calls and host work).
  double build_seconds = 0.0;

 private:
  OccupancyGrid(const GridBox& box, std::array<int, 3> dims);  // geometry only (no cells)
  GridBox box_;
  std::array<int, 3> dims_{};
  std::vector<uint8_t> cells_;
  cl::Buffer buf_;
};

// A 3³ max filter applied `steps` times (cells of dims, x fastest); the host half of build().
std::vector<uint8_t> dilate_cells(const std::vector<uint8_t>& cells, std::array<int, 3> dims,
                                  int steps);

}  // namespace sgnlf::render
