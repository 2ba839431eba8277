// EncodingReuse: launches kernels/pipeline/encoding_reuse.cl.
#include "pipeline/model/encoding_reuse.hpp"

#include "pipeline/model/model_detail.hpp"

namespace sgnlf::pipeline {
using namespace model_detail;

EncodingReuse::EncodingReuse(cl::Runtime& rt, int max_rays, int n_samples, int n_importance,
                             int width)
    : S_(n_samples),
      I_(n_importance),
      width_(width),
      fine_points_(rt.kernel("pipeline/encoding_reuse.cl", "pipeline_fine_points")),
      merge_(rt.kernel("pipeline/encoding_reuse.cl", "pipeline_merge_encodings")) {
  const size_t R = size_t(max_rays), I = size_t(n_importance);
  const size_t N = R * size_t(n_samples + n_importance);
  src_ = floats(rt, N);  // int32 per merged sample
  x_f_ = floats(rt, R * I * 3), enc_f_ = floats(rt, R * I * size_t(width));
}

void EncodingReuse::encode_importance(int n_rays, const cl::Buffer& x, field::Encoder& encoder,
                                      const cl::Buffer& params, size_t offset) {
  const int M = S_ + I_;
  fine_points_.set_args(n_rays, S_, M, src_, x, x_f_);
  fine_points_.launch({cl::round_up(size_t(n_rays) * size_t(M), 64)}, {64});
  encoder.forward(params, offset, x_f_, n_rays * I_, enc_f_);
}

void EncodingReuse::merge(int n_rays, const cl::Buffer& x_c, const cl::Buffer& enc_c,
                          cl::Buffer& x, cl::Buffer& enc) {
  const int M = S_ + I_;
  merge_.set_args(n_rays, S_, M, width_, src_, x_c, enc_c, enc_f_, x, enc);
  merge_.launch({cl::round_up(size_t(n_rays) * size_t(M), 64)}, {64});
}

}  // namespace sgnlf::pipeline
