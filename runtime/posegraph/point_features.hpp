// Per-point features for the confidence-aware pose graph (method.md §4.2): the caller supplies
// them. In SG-NLF they are the field's hybrid features f_hyb = [hash-grid features, λΨ(x)]
// evaluated at the points' world positions under the current poses (on the OpenCL device); the
// pose graph only needs a function from world points to n × dim features. Matching uses cosine
// similarity, so the graph normalises each row (unit_features).
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
};

// The provider's features at `x_world`, each row scaled to unit length (a zero row stays zero:
// its cosine similarity with anything is 0). Throws sgnlf::Error when the provider is empty, has
// dim < 1, returns the wrong number of values, and sgnlf::NumericError for a non-finite value.
std::vector<float> unit_features(const FeatureProvider& f,
                                 const std::vector<Eigen::Vector3f>& x_world);

// Cosine similarity of two unit rows of length dim (float, summed in index order).
inline float cosine(const float* a, const float* b, int dim) {
  float s = 0.f;
  for (int k = 0; k < dim; ++k) s += a[k] * b[k];
  return s;
}

}  // namespace sgnlf::posegraph
