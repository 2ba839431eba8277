// The coarse pass and the importance samples that importance sampling and early termination
// share (sampler_base.hpp).
#include "pipeline/model/samplers/sampler_base.hpp"

namespace sgnlf::pipeline::samplers {

long coarse_pass(SamplerBase& b, const SampleRequest& r, CoarseWaves* waves) {
  const int n_c = r.n_rays * b.S;
  b.parts.rays.uniform(b.buf.origins, b.buf.directions, r.n_rays, r.jitter, r.seed, r.step,
                       b.buf.t_c, b.buf.x_c);
  b.field.clamp(b.buf.x_c, n_c);
  const auto weights = [&] { b.field.weights(b.buf.t_c, b.buf.h0, r.n_rays, b.S, b.buf.w_c); };
  if (waves)
    return waves->run(r.n_rays, b.buf.x_c, b.buf.w_c, b.buf.enc_c, b.buf.h0, b.field.density,
                      weights);
  const cl::Buffer& dens = b.field.density(b.buf.x_c, n_c, b.buf.enc_c);
  b.field.sigma(dens, n_c, b.buf.h0);
  weights();
  return n_c;
}

SampleSet importance_pass(SamplerBase& b, const SampleRequest& r, CoarseWaves* waves) {
  SampleSet s;
  s.coarse = coarse_pass(b, r, waves);
  EncodingReuse& reuse = *b.parts.reuse;
  b.parts.rays.importance(b.buf.origins, b.buf.directions, r.n_rays, b.S, b.buf.t_c, b.buf.w_c,
                          r.jitter, r.seed, r.step, b.buf.t, b.buf.x, reuse.sources());
  const int M = b.S + b.I;
  b.field.clamp(b.buf.x, r.n_rays * M);
  // The merged set's coarse samples were encoded by the coarse pass with the same parameters:
  // only the importance samples need the hash grid (exact; the coarse positions are copied
  // over so that the backward scatters where the forward read).
  if (r.reuse_encodings)
    reuse.encode_importance(r.n_rays, b.buf.x, b.field.encoder, b.field.params,
                            b.field.grid_offset);
  reuse.merge(r.n_rays, b.buf.x_c, b.buf.enc_c, b.buf.x, b.buf.enc);
  s.n_rays = r.n_rays, s.per_ray = M, s.rows = s.samples();
  s.encoded = r.reuse_encodings;
  return s;
}

}  // namespace sgnlf::pipeline::samplers
