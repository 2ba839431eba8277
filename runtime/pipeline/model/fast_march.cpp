// FastMarch: launches kernels/pipeline/fast_march.cl.
#include "pipeline/model/fast_march.hpp"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "pipeline/model/model_detail.hpp"

namespace sgnlf::pipeline {
using namespace model_detail;

namespace {
constexpr const char* kFile = "pipeline/fast_march.cl";
size_t g64(size_t n) { return cl::round_up(std::max<size_t>(n, 1), 64); }
}  // namespace

FastMarch::FastMarch(cl::Runtime& rt, int max_rays, int max_samples,
                     const render::FastRenderConfig& cfg)
    : cfg_(cfg),
      list_k_(rt.kernel(kFile, "pipeline_occupied_list")),
      gather_k_(rt.kernel(kFile, "pipeline_march_gather")),
      scatter_k_(rt.kernel(kFile, "pipeline_march_scatter")),
      done_k_(rt.kernel(kFile, "pipeline_march_done")),
      hcount_k_(rt.kernel(kFile, "pipeline_head_count")),
      hgather_k_(rt.kernel(kFile, "pipeline_head_gather")),
      hscatter_k_(rt.kernel(kFile, "pipeline_head_scatter")),
      fill_k_(rt.kernel(kFile, "pipeline_march_fill")),
      prefill_k_(rt.kernel(kFile, "pipeline_march_prefill")) {
  cfg_.validate();
  const size_t R = size_t(max_rays), N = R * size_t(max_samples);
  idx_ = floats(rt, N), count_ = floats(rt, R), alive_ = floats(rt, R), cursor_ = floats(rt, R);
  offset_ = floats(rt, R + 1), last_ = floats(rt, R), done_ = floats(rt, R);
  x_w_ = floats(rt, N * 3), row_q_ = floats(rt, N), dens_full_ = floats(rt, N * kDensStride);
  h_offset_ = floats(rt, R + 1), dens_h_ = floats(rt, N * kDensStride), h_q_ = floats(rt, N);
  h_ray_ = floats(rt, N), hcount_ = floats(rt, R);
  h0_prev_ = floats(rt, N), dens_prev_ = floats(rt, N * kDensStride), known_ = floats(rt, N);
}

long FastMarch::density_pass(int n_rays, int S, const cl::Buffer& x,
                             const render::OccupancyGrid& grid, cl::Buffer& h0, cl::Buffer& head,
                             const cl::Buffer& w, const Density& density,
                             const Weights& weights) {
  const int n = n_rays * S;
  fill_k_.set_args(n, kDeadLogit, kOffLogit, h0, head).launch({g64(size_t(n))}, {64});
  list_k_.set_args(n_rays, S, grid.lo4(), grid.inv_cell4(), grid.dims4(), grid.device(), x, 0,
                   known_, idx_, count_)
      .launch({g64(size_t(n_rays))}, {64});
  return march(n_rays, S, x, h0, w, density, weights);
}

long FastMarch::merged_pass(int n_rays, int S_c, int M, const cl::Buffer& x,
                            const cl::Buffer& sources, const render::OccupancyGrid& grid,
                            cl::Buffer& h0, cl::Buffer& head, const cl::Buffer& w,
                            const Density& density, const Weights& weights) {
  require(S_c > 0 && S_c <= M, "FastMarch::merged_pass: " + std::to_string(S_c) +
                                   " coarse samples of " + std::to_string(M));
  // The coarse pass's logits and density rows move aside before the merged layout overwrites
  // them.
  h0_prev_.copy_from(h0, size_t(n_rays) * size_t(S_c) * sizeof(float));
  std::swap(dens_full_, dens_prev_);
  const int n = n_rays * M;
  fill_k_.set_args(n, kDeadLogit, kOffLogit, h0, head).launch({g64(size_t(n))}, {64});
  prefill_k_.set_args(n, S_c, M, kDensStride, kDeadLogit, sources, h0_prev_, dens_prev_, h0,
                      dens_full_, known_)
      .launch({g64(size_t(n))}, {64});
  list_k_.set_args(n_rays, M, grid.lo4(), grid.inv_cell4(), grid.dims4(), grid.device(), x, 1,
                   known_, idx_, count_)
      .launch({g64(size_t(n_rays))}, {64});
  return march(n_rays, M, x, h0, w, density, weights);
}

long FastMarch::march(int n_rays, int S, const cl::Buffer& x, cl::Buffer& h0,
                      const cl::Buffer& w, const Density& density, const Weights& weights) {
  const std::vector<int32_t> count = count_.read_vec<int32_t>(size_t(n_rays));
  std::vector<int32_t> cursor(size_t(n_rays), 0), alive;
  for (int r = 0; r < n_rays; ++r)
    if (count[size_t(r)] > 0) alive.push_back(r);
  long evaluated = 0;
  std::vector<int32_t> cur_a, off_a, end_a;
  for (int wave = 0; !alive.empty(); ++wave) {
    // `wave` samples per ray, doubling; the last wave (max_waves) takes every sample left: the
    // rays still going then are the translucent ones, which need most of their samples anyway.
    const int K = wave + 1 >= cfg_.max_waves ? S : std::min(S, cfg_.wave << std::min(wave, 16));
    const size_t A = alive.size();
    cur_a.assign(A, 0), off_a.assign(A + 1, 0), end_a.assign(A, 0);
    for (size_t a = 0; a < A; ++a) {
      const size_t r = size_t(alive[a]);
      const int take = std::min(K, count[r] - cursor[r]);
      cur_a[a] = cursor[r];
      off_a[a + 1] = off_a[a] + take;
      cursor[r] += take;
      end_a[a] = cursor[r];
    }
    const int rows = off_a.back();
    alive_.write(alive.data(), A * 4);
    cursor_.write(cur_a.data(), A * 4);
    offset_.write(off_a.data(), (A + 1) * 4);
    last_.write(end_a.data(), A * 4);
    gather_k_.set_args(int(A), S, K, alive_, cursor_, offset_, idx_, x, x_w_, row_q_)
        .launch({g64(A * size_t(K))}, {64});
    const cl::Buffer& dens = density(x_w_, rows);
    scatter_k_.set_args(rows, kDensStride, row_q_, dens, h0, dens_full_)
        .launch({g64(size_t(rows))}, {64});
    evaluated += rows;
    weights();
    // One host sync per wave: which rays go on (not terminated, occupied samples left).
    done_k_.set_args(int(A), S, cfg_.stop_transmittance, alive_, last_, idx_, w, done_)
        .launch({g64(A)}, {64});
    const std::vector<int32_t> done = done_.read_vec<int32_t>(A);
    std::vector<int32_t> next;
    for (size_t a = 0; a < A; ++a) {
      const size_t r = size_t(alive[a]);
      if (!done[a] && cursor[r] < count[r]) next.push_back(alive[a]);
    }
    alive.swap(next);
  }
  return evaluated;
}

long FastMarch::head_pass(int n_rays, int S, const cl::Buffer& w, cl::Buffer& head,
                          const Head& run_head) {
  const float thr = cfg_.head_weight_threshold;
  hcount_k_.set_args(n_rays, S, thr, w, hcount_).launch({g64(size_t(n_rays))}, {64});
  const std::vector<int32_t> count = hcount_.read_vec<int32_t>(size_t(n_rays));
  std::vector<int32_t> offset(size_t(n_rays) + 1, 0);
  for (int r = 0; r < n_rays; ++r) offset[size_t(r) + 1] = offset[size_t(r)] + count[size_t(r)];
  const int rows = offset.back();
  if (rows == 0) return 0;
  h_offset_.write(offset.data(), offset.size() * 4);
  hgather_k_.set_args(n_rays, S, kDensStride, thr, w, h_offset_, dens_full_, dens_h_, h_q_, h_ray_)
      .launch({g64(size_t(n_rays))}, {64});
  const field::GroupIndex index{&h_ray_, &h_offset_, n_rays};
  const cl::Buffer& out = run_head(dens_h_, rows, index);
  hscatter_k_.set_args(rows, h_q_, out, head).launch({g64(size_t(rows))}, {64});
  return rows;
}

}  // namespace sgnlf::pipeline
