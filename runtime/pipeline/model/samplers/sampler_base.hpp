// What the built-in strategies of this folder share: the context's parts, buffers and field
// with the uniform and importance counts, and the density-only coarse pass of importance
// sampling and early termination. Private to samplers/.
#pragma once
#include <string>

#include "core/error.hpp"
#include "pipeline/model/sampler.hpp"

namespace sgnlf::pipeline::samplers {

struct SamplerBase : Sampler {
  explicit SamplerBase(const SamplerContext& c)
      : S(c.render.n_samples), I(c.render.n_importance), parts(c.parts), buf(c.buffers),
        field(c.field) {}
  int S, I;
  SamplerParts parts;
  SampleBuffers buf;
  SamplerField field;
};

// The density-only pass over the uniform samples (t_c, x_c): encodings into enc_c, σ logits into
// h0, weights into w_c; in waves with `waves` (render.coarse_waves > 1), else in one pass.
// Returns the samples evaluated.
long coarse_pass(SamplerBase& b, const SampleRequest& r, CoarseWaves* waves);

// Importance sampling (n_importance > 0): the coarse pass, n_importance samples per ray drawn
// from its weights and merged, the coarse encodings reused when the request allows. The set's
// layout, encodings and coarse count; its strategy is the caller's.
SampleSet importance_pass(SamplerBase& b, const SampleRequest& r, CoarseWaves* waves);

// ConfigError naming `key` (the key that chose the strategy) when `ok` is false: `what` says
// which setting the strategy needs.
inline void require_setting(bool ok, const std::string& key, const char* strategy,
                            const char* what) {
  if (!ok)
    throw ConfigError(key + ": the '" + strategy + "' sampler needs " + what);
}

}  // namespace sgnlf::pipeline::samplers
