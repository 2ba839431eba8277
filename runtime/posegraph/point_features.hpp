// Per-point features for the confidence-aware pose graph (method.md §4.2): the caller supplies
// them. In SG-NLF they are the field's hybrid features f_hyb = [hash-grid features, λΨ(x)]
// evaluated at the points' world positions under the current poses (on the OpenCL device); the
// pose graph only needs a function from world points to n × dim features. Matching uses cosine
// similarity, so the graph normalises each row (unit_features), part by part when the provider
// says its features are made of parts of different kinds (f_hyb: [f_geo, λΨ]).
#pragma once
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sgnlf::posegraph {

// Fills `out` with x_world.size() × dim features, row-major (row k belongs to x_world[k]).
// Points are in metres in the world frame of the poses given to the graph builder; a provider
// that works in normalised coordinates converts them itself.
using FeatureFn =
    std::function<void(const std::vector<Eigen::Vector3f>& x_world, std::vector<float>& out)>;

struct FeatureProvider {
  int dim = 0;
  FeatureFn eval;
  std::string name;  // shown in reports, e.g. "f_hyb" or "stand-in: random Fourier features"
  // Widths of consecutive parts of a row (sum dim), each normalised on its own; empty: one part.
  std::vector<int> parts;
};

// The provider's features at `x_world`, each row scaled to unit length (a zero row stays zero:
// its cosine similarity with anything is 0). With parts, each non-zero part of a row is scaled
// to length 1/sqrt(m), m the row's non-zero parts, so the row has unit length and the cosine of
// two rows is the mean of their parts' cosines when both have the same parts non-zero. Throws
// sgnlf::Error when the provider is empty, has dim < 1, parts that do not sum to dim or returns
// the wrong number of values, and sgnlf::NumericError for a non-finite value.
std::vector<float> unit_features(const FeatureProvider& f,
                                 const std::vector<Eigen::Vector3f>& x_world);

// Cosine similarity of two unit rows of length dim (float, summed in index order).
inline float cosine(const float* a, const float* b, int dim) {
  float s = 0.f;
  for (int k = 0; k < dim; ++k) s += a[k] * b[k];
  return s;
}

}  // namespace sgnlf::posegraph
