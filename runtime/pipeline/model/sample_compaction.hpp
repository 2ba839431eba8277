// Early ray termination's sample compaction (render.stop_transmittance > 0 with a coarse pass;
// kernels/pipeline/sample_compaction.cl): merged samples behind the point where the coarse
// pass's transmittance fell below the threshold carry weight below it and are not evaluated.
// Their live prefix of each ray is gathered into a compact layout (live rows only, ray by ray)
// that the field runs on; the field's outputs are expanded back into the full layout the
// renderer reads (dead samples at zero density), and the renderer's gradients gathered into the
// compact layout again. Owns the per-ray live offsets, each live row's ray, and the live rows'
// positions, encodings, head outputs and gradients. select() and counts() block; the other
// calls only enqueue.
#pragma once
#include <memory>
#include <vector>

#include "cl/runtime.hpp"
#include "field/encoder.hpp"
#include "field/mlp.hpp"

namespace sgnlf::pipeline {

class SampleCompaction {
 public:
  // Capacity: max_rays rays of up to max_samples merged samples of n_samples coarse ones;
  // `width` floats per encoding; eps = render.stop_transmittance.
  SampleCompaction(cl::Runtime& rt, int max_rays, int max_samples, int n_samples, int width,
                   float eps);
  ~SampleCompaction();

  // Counts the live samples of each of n_rays rays (M per ray at t, the coarse pass's t_c and
  // weights w_c: n_samples per ray), sums them into the per-ray offsets and gathers the live
  // rows of the positions x (n_rays × M × 3) into positions(). Returns the live rows. The
  // device profile's `compaction` chooses, when this object is made, where the sum runs (an
  // OffsetSum): host = one blocking read of n_rays ints and one blocking write of the offsets;
  // device = the scan on the device (pipeline_offsets_scan) and one blocking read of the total.
  // The same offsets either way.
  long select(int n_rays, int M, const cl::Buffer& t_c, const cl::Buffer& w_c,
              const cl::Buffer& t, const cl::Buffer& x);
  // encodings() from the live rows of enc (n_rays × M × width, already encoded), or by
  // encoding positions() with `encoder` (its parameters at `offset` of `params`).
  void gather_encodings(int n_rays, int M, const cl::Buffer& enc);
  void encode(field::Encoder& encoder, const cl::Buffer& params, size_t offset);
  // The field's outputs on the live rows into the full layout: h0 (n_rays × M) from column 0 of
  // dens (kDensStride floats per live row) and head (n_rays × M × 2) from head_out(); dead
  // samples get h0 = kDeadLogit and head = 0.
  void expand(int n_rays, int M, const cl::Buffer& dens, cl::Buffer& h0, cl::Buffer& head);
  // The renderer's gradients dL/dh0 (and dL/dhead when given; full layout) on the live rows,
  // into grad_h0() (and grad_head()).
  void gather_gradients(int n_rays, int M, const cl::Buffer& g_h0, const cl::Buffer* g_head);
  // ray[k] = r for the rows k of ray r of any per-ray offsets (n_rays + 1 int32s): each live
  // row's ray here, each band row's ray for pipeline::HeadBand.
  void row_rays(int n_rays, const cl::Buffer& offset, cl::Buffer& ray);

  long rows() const { return rows_; }
  const cl::Buffer& offsets() const { return offset_; }  // n_rays + 1 (int32)
  // The live rows' groups for field::Mlp's grouped input (the head's direction encoding).
  field::GroupIndex index(int n_rays) const { return {&row_ray_, &offset_, n_rays}; }
  // Live samples per ray of the last select() of n_rays rays. Blocking.
  std::vector<int> counts(int n_rays) const;
  const cl::Buffer& positions() const { return x_l_; }
  const cl::Buffer& encodings() const { return enc_l_; }
  cl::Buffer& head_out() { return head_l_; }
  const cl::Buffer& grad_h0() const { return g_h0_l_; }
  const cl::Buffer& grad_head() const { return g_head_l_; }

 private:
  int S_, width_;
  float eps_;
  long rows_ = 0;
  cl::Kernel live_count_, compact_rows_, expand_, row_ray_k_;
  // The per-ray counts' sum into offsets: one class per value of the profile's compaction
  // (sample_compaction.cpp), chosen when made.
  class OffsetSum;
  class HostOffsetSum;
  class DeviceOffsetSum;
  std::unique_ptr<OffsetSum> sum_;
  // The profile's ray_work_items and local_size when made: above 1, the counts and the row →
  // ray map run ray_wi_ work-items per ray (pipeline_live_count_wide, pipeline_row_ray_wide).
  int ray_wi_, ray_wg_;
  void launch_live_count(int n_rays);
  // Per-ray live offsets (int32), each live row's ray, and the live rows' positions,
  // encodings, head outputs and their gradients.
  cl::Buffer offset_, row_ray_, x_l_, enc_l_, head_l_, g_h0_l_, g_head_l_;
};

}  // namespace sgnlf::pipeline
