// STAND-IN features for the confidence-aware pose graph, for tests, benchmarks and
// `sgnlf posegraph --graph confidence`: NOT the field's f_hyb. Random Fourier features of the
// world position, a deterministic smooth function of x_world alone:
//   f(x) = [cos(2π w_k·x / λ_k), sin(2π w_k·x / λ_k)]_{k=1..F} / √F,
// w_k a unit direction (normalised Gaussian draws) and λ_k log-uniform in [min, max] wavelength,
// both from the project's Rng(seed). |f| = 1 and cos(f(x), f(y)) = mean_k cos(2π w_k·(x − y)/λ_k):
// the similarity depends on the displacement only, ≈ 1 for points a few centimetres apart and
// decorrelating over ~min wavelength. Like f_hyb it is one function of world position shared by
// all frames, so two frames' points agree where the current poses put them on top of each other.
#pragma once
#include <cstdint>

#include "posegraph/point_features.hpp"

namespace sgnlf::posegraph {

struct StandinFeatureConfig {
  int frequencies = 16;            // dim = 2 · frequencies
  double min_wavelength_m = 1.0;
  double max_wavelength_m = 10.0;
  uint64_t seed = 1;
  void validate() const;  // ConfigError naming the field
};

FeatureProvider standin_fourier_features(const StandinFeatureConfig& c = {});

}  // namespace sgnlf::posegraph
