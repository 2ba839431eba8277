// The position encoding that feeds the density MLP (method.md §0 "Field", §4.1): a model calls
// forward/backward through this interface and never names the encoding. Implementations: the
// hash grid (hash_grid_encoder.hpp; LiDAR-NeRF, GeoNLF) and SG-NLF's hybrid [f_geo, λ·Ψ(x)]
// (spectral/hybrid_encoder.hpp); LiDAR4D's planes would be a third.
// Parameters trained by the range loss live in the model's flat buffer at the offset the model
// gives; an encoder may also own parameters trained on their own schedule (Ψ), which it
// checkpoints itself.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "cl/runtime.hpp"

namespace sgnlf::field {

class Encoder {
 public:
  virtual ~Encoder() = default;
  // Output features per point (the density MLP's input width).
  virtual int width() const = 0;
  // How the width() output features split into parts of different kinds, in order (sums to
  // width()): one part by default; the hybrid encoder's [f_geo, λΨ] are two. Users comparing
  // features (the pose graph's cosine matching) normalise each part on its own so that one part
  // cannot dominate the similarity by its scale.
  virtual std::vector<int> parts() const { return {width()}; }
  // Floats in the model's flat parameter buffer.
  virtual size_t n_params() const = 0;
  // Deterministic initialisation of host_params[offset, offset + n_params()) (and of any
  // parameters the encoder owns) from `seed`.
  virtual void init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) = 0;
  // enc (N × width) of x (N × 3, normalised box). Enqueued, no wait.
  virtual void forward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
                       cl::Buffer& enc) = 0;
  // From d_enc (N × width): overwrites grad[grad_offset, + n_params()); writes dL/dx (N × 3)
  // when d_x is given (pose gradients). `x` as in the preceding forward. Enqueued, no wait.
  virtual void backward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
                        const cl::Buffer& d_enc, cl::Buffer& grad, size_t grad_offset,
                        cl::Buffer* d_x) = 0;
  // Coarse-to-fine mask over the encoding's levels (BARF, method.md §3); levels() = 0 when the
  // encoding has none. Blocking upload, between steps.
  virtual int levels() const = 0;
  virtual void set_level_weights(const std::vector<float>& w) = 0;
};

}  // namespace sgnlf::field
