// Progressive spectral-geometric fusion (method.md §4.1): f_hyb = [f_geo, λ(t)·Ψ(x)] feeds the
// density MLP and is the feature used for matching (pose graph, §4.2). λ ramps linearly from 0
// to 1 over a configured window of iterations; with λ = 0 the density MLP sees [f_geo, 0], so
// the field behaves exactly as without the spectral part (tests/spectral/test_fusion.cpp).
#pragma once
#include "cl/runtime.hpp"
#include "core/config_fwd.hpp"
#include "spectral/fusion_ramp.hpp"

namespace sgnlf::spectral {

class SpectralFusion {
 public:
  // geo_width = L·F of the encoding, k = Ψ's outputs.
  SpectralFusion(cl::Runtime& rt, int geo_width, int k);
  int fusion_width() const { return geo_width_ + k_; }
  int geo_width() const { return geo_width_; }
  int k() const { return k_; }
  // hyb (N × (G+K)) = [geo (N × G), λ·psi (N × K)]. Enqueued, no wait.
  void forward(const cl::Buffer& geo, const cl::Buffer& psi, int n, float lambda, cl::Buffer& hyb);
  // d_psi = λ·d_hyb[:, G:] (overwritten); d_geo = d_hyb[:, :G] when given. Enqueued, no wait.
  void backward(const cl::Buffer& d_hyb, int n, float lambda, cl::Buffer* d_geo, cl::Buffer& d_psi);

 private:
  int geo_width_, k_;
  cl::Kernel fwd_, bwd_;
};

}  // namespace sgnlf::spectral
