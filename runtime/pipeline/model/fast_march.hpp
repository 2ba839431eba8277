// The fast renderer's marching (render::FastRenderConfig; kernels/pipeline/fast_march.cl): of
// each ray's samples only those in occupied cells of a render::OccupancyGrid are evaluated,
// front to back in waves (`wave` samples per ray, doubling, the last of max_waves taking every
// sample left) until the ray's transmittance
// falls below stop_transmittance; the others keep a dead σ (zero weight). The LiDAR head then
// runs only on the samples whose weight exceeds head_weight_threshold (head logits kOffLogit
// elsewhere). The sample layout is the protocol renderer's (S per ray, ray-major), so the
// volume renderer reads the result as it reads the protocol's. Owns the per-ray occupied
// sample lists and the wave and head rows. density_pass() and head_pass() block once per wave.
#pragma once
#include <functional>

#include "cl/runtime.hpp"
#include "field/mlp.hpp"
#include "render/fast_render_config.hpp"
#include "render/occupancy_grid.hpp"

namespace sgnlf::pipeline {

class FastMarch {
 public:
  // Capacity: max_rays rays of up to max_samples samples.
  FastMarch(cl::Runtime& rt, int max_rays, int max_samples, const render::FastRenderConfig& cfg);

  // The density MLP's output (kDensStride floats per row) at `rows` positions x (rows × 3).
  using Density = std::function<const cl::Buffer&(const cl::Buffer& x, int rows)>;
  // The weights of every ray (full layout) from the current h0, into the w given to the pass.
  using Weights = std::function<void()>;
  // The head's output (2 per row) on `rows` density rows grouped by ray (index).
  using Head = std::function<const cl::Buffer&(const cl::Buffer& dens, int rows,
                                               const field::GroupIndex& index)>;

  // Fills h0 (n_rays × S: σ logits, kDeadLogit where not evaluated) and head (× 2: kOffLogit)
  // for samples x (n_rays × S × 3), and leaves the weights in w. Returns the samples evaluated.
  long density_pass(int n_rays, int S, const cl::Buffer& x, const render::OccupancyGrid& grid,
                    cl::Buffer& h0, cl::Buffer& head, const cl::Buffer& w,
                    const Density& density, const Weights& weights);
  // The merged pass of importance sampling, right after density_pass on the coarse samples
  // (S_c per ray, whose logits h0 still holds): the M merged samples x, `sources` as
  // render::RaySampler::importance writes them (k < S_c: coarse sample k). Merged samples whose
  // coarse source the coarse pass evaluated take its logit and density row without being
  // evaluated again; the others march as in density_pass. Fills h0 (n_rays × M) and head, leaves
  // the weights in w; returns the samples evaluated.
  long merged_pass(int n_rays, int S_c, int M, const cl::Buffer& x, const cl::Buffer& sources,
                   const render::OccupancyGrid& grid, cl::Buffer& h0, cl::Buffer& head,
                   const cl::Buffer& w, const Density& density, const Weights& weights);
  // The head on the samples of the last density_pass or merged_pass whose weight w exceeds the threshold,
  // into head (full layout). Returns the rows it ran on.
  long head_pass(int n_rays, int S, const cl::Buffer& w, cl::Buffer& head, const Head& run_head);

 private:
  // The waves over the listed samples (idx_, count_) of a pass.
  long march(int n_rays, int S, const cl::Buffer& x, cl::Buffer& h0, const cl::Buffer& w,
             const Density& density, const Weights& weights);

  render::FastRenderConfig cfg_;
  cl::Kernel list_k_, gather_k_, scatter_k_, done_k_, hcount_k_, hgather_k_, hscatter_k_, fill_k_,
      prefill_k_;
  // Per ray: occupied sample indices and counts; per alive ray: ray, cursor, row offsets,
  // last evaluated sample, done flag; per wave row: position and full-layout index; the density
  // rows in the full layout; the head rows (density input, index, ray, output).
  cl::Buffer idx_, count_, alive_, cursor_, offset_, last_, done_, x_w_, row_q_, dens_full_,
      h_offset_, dens_h_, h_q_, h_ray_, hcount_;
  // The merged pass: the coarse pass's logits and density rows, and which merged samples they
  // give.
  cl::Buffer h0_prev_, dens_prev_, known_;
};

}  // namespace sgnlf::pipeline
