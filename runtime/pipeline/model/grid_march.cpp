// GridMarch: launches kernels/pipeline/grid_march.cl.
#include "pipeline/model/grid_march.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/error.hpp"
#include "pipeline/model/model_detail.hpp"

namespace sgnlf::pipeline {
using namespace model_detail;

namespace {
constexpr const char* kFile = "pipeline/grid_march.cl";
size_t g64(size_t n) { return cl::round_up(std::max<size_t>(n, 1), 64); }
}  // namespace

GridMarch::GridMarch(cl::Runtime& rt, int max_rays, int max_wave,
                     const render::FastRenderConfig& cfg)
    : cfg_(cfg), max_rays_(max_rays), max_wave_(max_wave),
      init_k_(rt.kernel(kFile, "pipeline_gm_init")),
      count_k_(rt.kernel(kFile, "pipeline_gm_count")),
      emit_k_(rt.kernel(kFile, "pipeline_gm_emit")),
      composite_k_(rt.kernel(kFile, "pipeline_gm_composite")),
      hgather_k_(rt.kernel(kFile, "pipeline_gm_head_gather")),
      hacc_k_(rt.kernel(kFile, "pipeline_gm_head_accumulate")),
      finish_k_(rt.kernel(kFile, "pipeline_gm_finish")) {
  cfg_.validate();
  require(max_rays > 0 && max_wave > 0, "GridMarch: capacity must be positive");
  const size_t R = size_t(max_rays), N = R * size_t(max_wave);
  cursor_ = floats(rt, R), trans_ = floats(rt, R), acc_ = floats(rt, 3 * R);
  median_ = floats(rt, R), alive_ = floats(rt, R), offset_ = floats(rt, R + 1);
  count_ = floats(rt, R), hcount_ = floats(rt, R), hoffset_ = floats(rt, R + 1);
  done_ = floats(rt, R), groups_ = floats(rt, R + 1);
  mode_ = floats(rt, R), quiet_ = floats(rt, R), last_k_ = floats(rt, R);
  k_w_ = floats(rt, N), cell_w_ = floats(rt, N), stats_ = floats(rt, 4 * R);
  x_w_ = floats(rt, 3 * N), t_w_ = floats(rt, N), dt_w_ = floats(rt, N), w_w_ = floats(rt, N);
  dens_h_ = floats(rt, N * kDensStride), w_h_ = floats(rt, N), ray_h_ = floats(rt, N);
}

void GridMarch::render(int n_rays, const cl::Buffer& o, const cl::Buffer& d,
                       const Lattice& L, const render::OccupancyGrid& grid, bool median,
                       const Density& density, const Head& head, cl::Buffer& out) {
  require(n_rays > 0 && n_rays <= max_rays_,
          "GridMarch::render: " + std::to_string(n_rays) + " rays, capacity " +
              std::to_string(max_rays_));
  require(L.samples > 0 && L.refine >= 1 && L.coarse >= 1 && L.bin > 0.0f,
          "GridMarch::render: the lattice needs samples, a positive bin, refine and coarse >= 1");
  const float h = L.bin / float(L.refine);
  const long K_long = long(L.samples) * long(L.refine);
  require(K_long < (1L << 30), "GridMarch::render: a lattice of " + std::to_string(K_long) +
                                   " points per ray is too fine");
  const int K = int(K_long), m = L.refine, mc = L.refine * L.coarse;
  const cl_float4 lo = grid.lo4(), inv = grid.inv_cell4();
  const cl_int4 dims = grid.dims4();
  evaluated_ = 0, head_rows_ = 0, waves_ = 0;

  const int start_fine = mc == 1 || cfg_.hit_alpha <= 0.0f ? 1 : 0;
  init_k_.set_args(n_rays, start_fine, cursor_, trans_, acc_, median_, mode_, quiet_, last_k_,
                   stats_)
      .launch({g64(size_t(n_rays))}, {64});
  std::vector<int32_t> alive(static_cast<size_t>(n_rays));
  for (int r = 0; r < n_rays; ++r) alive[size_t(r)] = r;
  alive_.write(alive.data(), alive.size() * 4);
  // The first wave's counts.
  const int K_w = std::min(cfg_.wave, max_wave_);
  count_k_.set_args(n_rays, K_w, L.near, h, m, K, mc, L.bound, lo, inv, dims, grid.device(), alive_,
                    o, d, cursor_, mode_, 0, done_, count_)
      .launch({g64(size_t(n_rays))}, {64});
  std::vector<int32_t> count = count_.read_vec<int32_t>(size_t(n_rays)), hcount, off, hoff, next;
  while (true) {
    // Drop the rays with nothing left (done, or at the lattice's end).
    next.clear();
    std::vector<int32_t> kept;
    for (size_t a = 0; a < alive.size(); ++a)
      if (count[a] > 0) next.push_back(alive[a]), kept.push_back(count[a]);
    if (next.empty()) break;
    alive.swap(next);
    count.swap(kept);
    const size_t A = alive.size();
    off.assign(A + 1, 0);
    for (size_t a = 0; a < A; ++a) off[a + 1] = off[a] + count[a];
    const int rows = off.back();
    alive_.write(alive.data(), A * 4);
    offset_.write(off.data(), (A + 1) * 4);
    emit_k_.set_args(int(A), L.near, h, m, K, mc, L.bound, lo, inv, dims, grid.device(), alive_, o, d,
                     cursor_, mode_, offset_, x_w_, t_w_, dt_w_, k_w_, cell_w_)
        .launch({g64(A)}, {64});
    const cl::Buffer& dens = density(x_w_, rows);
    evaluated_ += rows;
    ++waves_;
    composite_k_.set_args(int(A), kDensStride, cfg_.stop_transmittance,
                          cfg_.head_weight_threshold, cfg_.hit_alpha, mc, alive_, offset_, dens,
                          t_w_, dt_w_, k_w_, cell_w_, trans_, acc_, median_, cursor_, mode_,
                          quiet_, last_k_, w_w_, hcount_, done_, stats_)
        .launch({g64(A)}, {64});
    count_k_.set_args(int(A), K_w, L.near, h, m, K, mc, L.bound, lo, inv, dims, grid.device(),
                      alive_, o, d, cursor_, mode_, 1, done_, count_)
        .launch({g64(A)}, {64});
    // One host sync per wave: the head rows of this wave and the next wave's counts.
    hcount = hcount_.read_vec<int32_t>(A);
    count = count_.read_vec<int32_t>(A);
    hoff.assign(A + 1, 0);
    for (size_t a = 0; a < A; ++a) hoff[a + 1] = hoff[a] + hcount[a];
    const int hrows = hoff.back();
    if (hrows > 0) {
      hoffset_.write(hoff.data(), (A + 1) * 4);
      hgather_k_.set_args(int(A), kDensStride, cfg_.head_weight_threshold, alive_, offset_,
                          hoffset_, dens, w_w_, dens_h_, w_h_, ray_h_)
          .launch({g64(A)}, {64});
      const field::GroupIndex index{&ray_h_, &groups_, n_rays};
      const cl::Buffer& hout = head(dens_h_, hrows, index);
      hacc_k_.set_args(int(A), alive_, hoffset_, hout, w_h_, acc_).launch({g64(A)}, {64});
      head_rows_ += hrows;
    }
  }
  const float t_last = L.near + (float(K) - 0.5f) * h;
  finish_k_.set_args(n_rays, int(median), t_last, acc_, median_, out)
      .launch({g64(size_t(n_rays))}, {64});
  const std::vector<int32_t> st = stats_.read_vec<int32_t>(4 * size_t(n_rays));
  rows_ = Rows{};
  for (size_t r = 0; r < size_t(n_rays); ++r)
    rows_.coarse += st[4 * r], rows_.fine += st[4 * r + 1], rows_.outside += st[4 * r + 2],
        rows_.dropped += st[4 * r + 3];
}

}  // namespace sgnlf::pipeline
