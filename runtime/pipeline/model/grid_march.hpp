// The fast renderer's marching with samples placed by the occupancy grid
// (render::FastRenderConfig layout "march"; kernels/pipeline/grid_march.cl): each ray walks a
// lattice m times finer than the protocol's bins: the protocol's spacing outside the grid's box
// and in occupied cells until a sample there stops more than hit_alpha of the light, then the
// fine step around it (rewinding one bin) until the ray is quiet again; free cells jumped over;
// in waves of `wave` samples per ray until its
// transmittance falls below stop_transmittance or the lattice ends. Each wave is composited as
// it comes (no full sample layout is kept) and the LiDAR head runs on its samples whose weight
// exceeds head_weight_threshold. One host sync per wave.
#pragma once
#include <functional>

#include "cl/runtime.hpp"
#include "field/mlp.hpp"
#include "render/fast_render_config.hpp"
#include "render/occupancy_grid.hpp"

namespace sgnlf::pipeline {

class GridMarch {
 public:
  // Capacity: max_rays rays, waves of up to max_wave samples per ray.
  GridMarch(cl::Runtime& rt, int max_rays, int max_wave, const render::FastRenderConfig& cfg);

  // The lattice of one render: the protocol's near and bin width (normalised), its S samples,
  // m = refine fine steps per bin, `coarse` bins per coarse step in occupied cells, the scene's
  // clamp bound.
  struct Lattice {
    float near = 0.0f, bin = 0.0f, bound = 1.0f;
    int samples = 0, refine = 1, coarse = 1;
  };
  // The density MLP's output (kDensStride floats per row) at `rows` positions x (rows × 3).
  using Density = std::function<const cl::Buffer&(const cl::Buffer& x, int rows)>;
  // The head's output (2 per row) on `rows` density rows, row k of ray index.point_group[k].
  using Head = std::function<const cl::Buffer&(const cl::Buffer& dens, int rows,
                                               const field::GroupIndex& index)>;

  // Renders n_rays rays (o, d: n × 3 on the device) into out (n × 3: depth, probability,
  // intensity; the median depth with `median`). Counts the density and head rows it ran.
  void render(int n_rays, const cl::Buffer& o, const cl::Buffer& d, const Lattice& lattice,
              const render::OccupancyGrid& grid, bool median, const Density& density,
              const Head& head, cl::Buffer& out);
  long evaluated() const { return evaluated_; }
  long head_rows() const { return head_rows_; }
  int waves() const { return waves_; }
  // The last render's density rows by kind: composited in occupied cells at the coarse and at
  // the fine spacing, outside the grid's box, and dropped after a hit (they sum to evaluated()).
  struct Rows {
    long coarse = 0, fine = 0, outside = 0, dropped = 0;
  };
  const Rows& rows() const { return rows_; }

 private:
  render::FastRenderConfig cfg_;
  int max_rays_, max_wave_;
  cl::Kernel init_k_, count_k_, emit_k_, composite_k_, hgather_k_, hacc_k_, finish_k_;
  // Per ray: lattice cursor, transmittance, sums (3), median; per alive ray: ray, row offsets,
  // counts, head counts, head offsets, done flags; per wave row: position, t, δ, weight; the
  // head rows: density row, weight, ray; an offsets buffer for the head's group index.
  cl::Buffer cursor_, trans_, acc_, median_, alive_, offset_, count_, hcount_, hoffset_, done_,
      x_w_, t_w_, dt_w_, w_w_, dens_h_, w_h_, ray_h_, groups_;
  // Per ray: fine or coarse mode, fine samples in a row below hit_alpha, the last composited
  // sample's lattice index; per wave row: its lattice index and whether in an occupied cell.
  cl::Buffer mode_, quiet_, last_k_, k_w_, cell_w_, stats_;
  Rows rows_;
  long evaluated_ = 0, head_rows_ = 0;
  int waves_ = 0;
};

}  // namespace sgnlf::pipeline
