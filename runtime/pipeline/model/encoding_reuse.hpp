// Reuse of the coarse pass's hash encodings in the merged pass of importance sampling
// (method.md §1; kernels/pipeline/encoding_reuse.cl): the merged sample set is the coarse
// samples plus the importance samples, and the coarse ones were already encoded with the same
// parameters, so only the importance samples go through the encoder; the merged positions and
// encodings are then assembled in sample order (the coarse positions copied from the coarse
// buffers, so that the backward scatters at the point the forward read). Owns the merged
// samples' sources and the importance samples' positions and encodings. Every call only
// enqueues.
#pragma once
#include "cl/runtime.hpp"
#include "field/encoder.hpp"

namespace sgnlf::pipeline {

class EncodingReuse {
 public:
  // Capacity: max_rays rays of n_samples coarse + n_importance importance samples; `width`
  // floats per encoding.
  EncodingReuse(cl::Runtime& rt, int max_rays, int n_samples, int n_importance, int width);

  // The merged samples' sources (int32, one per merged sample; render::RaySampler::importance
  // writes them): k < n_samples for coarse sample k, n_samples + j for importance sample j.
  cl::Buffer& sources() { return src_; }
  // Encodes the importance samples among the merged positions x (n_rays × M × 3) with `encoder`
  // (its parameters at `offset` of `params`).
  void encode_importance(int n_rays, const cl::Buffer& x, field::Encoder& encoder,
                         const cl::Buffer& params, size_t offset);
  // The merged rows in sample order: coarse sources copy their position (into x) and encoding
  // from x_c / enc_c, importance sources their encoding from encode_importance()'s.
  void merge(int n_rays, const cl::Buffer& x_c, const cl::Buffer& enc_c, cl::Buffer& x,
             cl::Buffer& enc);

 private:
  int S_, I_, width_;
  cl::Kernel fine_points_, merge_;
  cl::Buffer src_, x_f_, enc_f_;  // sources (int32); importance positions and encodings
};

}  // namespace sgnlf::pipeline
