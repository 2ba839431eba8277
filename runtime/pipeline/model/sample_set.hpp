// What a sampler (sampler.hpp) hands the field's forward: which strategy placed the samples of
// one pass, their layout, and what is already done for the field (encodings present, the live
// rows of early termination, the density-only pass's cost). Plain data, copied into the
// pass's ForwardContext (forward_context.hpp).
#pragma once
#include <string>

namespace sgnlf::pipeline {

struct SampleSet {
  // The registered name of the strategy that placed the samples (sampler.hpp; the built-in
  // ones, samplers/*.cpp: "uniform", "importance", "terminated", "surface").
  std::string strategy;
  int n_rays = 0;
  int per_ray = 0;        // samples per ray of the full layout the renderer reads (M)
  // The field's input encodings are already present: in the full layout (importance with
  // reuse) or in the live rows (terminated, always). False: the forward encodes the positions.
  bool encoded = false;
  // Early termination: the field runs on the live rows (pipeline::SampleCompaction), the
  // renderer on the full layout with the dead samples at zero density.
  bool compacted = false;
  long rows = 0;          // rows the field evaluates: n_rays × per_ray, or the live rows
  long coarse = 0;        // density-pass samples evaluated (0 without a coarse pass)
  long samples() const { return long(n_rays) * long(per_ray); }
};

}  // namespace sgnlf::pipeline
