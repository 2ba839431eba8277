// Head band (render.head_weight_threshold > 0 with early ray termination; LiDAR-NeRF evaluates
// its heads only where the weight exceeds 1e-4; kernels/pipeline/head_band.cl): per ray, the
// contiguous band of its live samples from the first to the last with weight above the
// threshold. The LiDAR head runs on the band rows only; every other sample gets head logits of
// kOffLogit (sigmoid ≈ 0), and the head's input gradient is zero outside the band. Rows of the
// live layout come from pipeline::SampleCompaction. Owns the per-ray band begin, count and
// offsets, each band row's ray, the band's density rows (the head's input), its head outputs
// and their gradients. select() blocks; the other calls only enqueue.
#pragma once
#include "cl/runtime.hpp"
#include "field/mlp.hpp"
#include "pipeline/model/sample_compaction.hpp"

namespace sgnlf::pipeline {

class HeadBand {
 public:
  // Capacity: max_rays rays of up to max_samples samples; `threshold` > 0.
  HeadBand(cl::Runtime& rt, int max_rays, int max_samples, float threshold);

  // Cuts each ray's band from the weights w (n_rays × M, full layout) over its live samples
  // (live.offsets()), with one blocking read of n_rays ints, and gathers the band's rows of the
  // density output dens (live layout, kDensStride floats per row) into density(). Returns the
  // band's rows.
  long select(int n_rays, int M, SampleCompaction& live, const cl::Buffer& w,
              const cl::Buffer& dens);
  // The band rows' groups for field::Mlp's grouped input (the head's direction encoding).
  field::GroupIndex index(int n_rays) const { return {&row_ray_, &offset_, n_rays}; }
  const cl::Buffer& density() const { return dens_b_; }  // the head's input rows
  cl::Buffer& head_out() { return head_b_; }             // the head's output rows (2 each)
  // head_out() into the full layout head (n_rays × M × 2), kOffLogit outside the band.
  void expand_head(int n_rays, int M, cl::Buffer& head);

  // Backward: the band's rows of dL/dhead (full layout) into grad_head(); the head's input
  // gradient (grad_density(), band rows) into the live rows of g_dens (kDensStride floats per
  // row: the band's rows, zeros elsewhere).
  void gather_head_gradient(int n_rays, int M, const SampleCompaction& live,
                            const cl::Buffer& g_head);
  const cl::Buffer& grad_head() const { return g_head_b_; }
  cl::Buffer& grad_density() { return g_dens_b_; }
  void scatter_density_gradient(int n_rays, int M, const SampleCompaction& live,
                                cl::Buffer& g_dens);

 private:
  float thr_;
  cl::Kernel band_k_, gather_, scatter_, expand_;
  // Per-ray begin / count / offsets (int32), each band row's ray, the band's density rows (head
  // input), head outputs and their gradients.
  cl::Buffer begin_, count_, offset_, row_ray_, dens_b_, head_b_, g_head_b_, g_dens_b_;
};

}  // namespace sgnlf::pipeline
