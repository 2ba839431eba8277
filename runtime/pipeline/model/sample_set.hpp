// What a sampler (sampler.hpp) hands the field's forward: which strategy placed the samples of
// one pass, their layout, and what is already done for the field (encodings present, the live
// rows of early termination, the density-only pass's cost). Plain data, copied into the
// pass's ForwardContext (forward_context.hpp).
#pragma once

namespace sgnlf::pipeline {

// The sampling strategies (sampler.hpp):
//   Uniform     n_samples stratified per ray, every sample evaluated (no coarse pass);
//   Importance  a density-only coarse pass over the uniform samples, n_importance samples drawn
//               from its weights and merged; the coarse encodings reused when allowed;
//   Terminated  early ray termination (render.stop_transmittance > 0): the coarse pass (in
//               render.coarse_waves waves) finds each ray's termination point and the field
//               runs on the live prefix of the uniform (n_importance = 0) or merged samples;
//   Surface     training samples placed by the measured return (render.surface_*).
enum class SampleStrategy { Uniform, Importance, Terminated, Surface };
const char* strategy_name(SampleStrategy s);

struct SampleSet {
  SampleStrategy strategy = SampleStrategy::Uniform;
  int n_rays = 0;
  int per_ray = 0;        // samples per ray of the full layout the renderer reads (M)
  // The field's input encodings are already present: in the full layout (Importance with
  // reuse) or in the live rows (Terminated, always). False: the forward encodes the positions.
  bool encoded = false;
  // Terminated: the field runs on the live rows (pipeline::SampleCompaction), the renderer on
  // the full layout with the dead samples at zero density.
  bool compacted = false;
  long rows = 0;          // rows the field evaluates: n_rays × per_ray, or the live rows
  long coarse = 0;        // density-pass samples evaluated (0 without a coarse pass)
  long samples() const { return long(n_rays) * long(per_ray); }
};

}  // namespace sgnlf::pipeline
